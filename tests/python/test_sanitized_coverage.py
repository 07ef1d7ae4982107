"""tools/sanitized_coverage's reading of gtest's output and its choice of
tests (pytest, run by ctest; the coverage build itself is the tool's run).

Environment as test_fit3dof.py: FIT3DOF_SOURCE_DIR the checkout.
"""

from tool_module import load_tool

tool = load_tool("sanitized_coverage")


def test_the_skipped_tests_are_read_off_gtests_summary():
    output = "\n".join([
        "[ RUN      ] Diagnose.A",
        "tests/diagnose_test.cc:10: Skipped",
        "three effects; plain build",
        "[  SKIPPED ] Diagnose.A (0 ms)",
        "[ RUN      ] Diagnose.B",
        "[       OK ] Diagnose.B (5 ms)",
        "[  SKIPPED ] 1 test, listed below:",
        "[  SKIPPED ] Diagnose.A",
    ])
    # gtest names a skipped test twice (as it ends and in the summary).
    assert tool.skipped_tests(output) == ["Diagnose.A"]


def test_the_greedy_choice_takes_lines_per_second_and_stops_when_none_gain():
    only = {("a.cc", n) for n in range(10)}
    per_test = {
        # 6 lines in 1 s: 3 per second, the best.
        "fast": ({("a.cc", n) for n in range(6)}, 1.0),
        # 8 lines in 7 s, 4 of them new after "fast": 0.5 per second.
        "slow": ({("a.cc", n) for n in range(2, 10)}, 7.0),
        # Nothing only skipped tests reach.
        "none": ({("b.cc", 1)}, 0.1),
        # Everything "fast" reaches: nothing left to gain after it.
        "same": ({("a.cc", n) for n in range(2)}, 0.0),
    }
    picked = tool.greedy(only, per_test)
    assert [p["test"] for p in picked] == ["fast", "slow"]
    assert [p["lines"] for p in picked] == [6, 4]
    assert picked[-1]["cumulative"] == 10
