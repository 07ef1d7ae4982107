"""A tool of tools/ (a Python script without the .py suffix) loaded as a
module, for the tests of its functions."""

import importlib.machinery
import importlib.util
import os


def load_tool(name):
    path = os.path.join(os.environ["FIT3DOF_SOURCE_DIR"], "tools", name)
    loader = importlib.machinery.SourceFileLoader(name, path)
    spec = importlib.util.spec_from_loader(name, loader)
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module
