// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// libFuzzer harness: a CSV data file (tools/fuzz). Any input must end in a
// record or an InputError.

#include <sanitizer/asan_interface.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <string>

#include "fit3dof/input_error.h"
#include "fit3dof/time_history.h"

// fast-cpp-csv-parser's LineReader allocates a block of 3 x 16 MB per reader
// (csv.h, block_len). Under ASan every such allocation maps fresh pages and
// its free poisons 6 MB of fresh shadow: 10 ms a run, a tenth of the rate
// the other harnesses reach. The harness keeps one such block between runs
// instead, unpoisoned while a reader owns it and poisoned otherwise, so an
// access to it outside a live reader is still reported.
namespace {

constexpr std::size_t kReaderBlock = std::size_t{3} << 24;
char* reader_block = nullptr;
bool reader_block_in_use = false;

}  // namespace

void* operator new[](std::size_t size) {
  if (size == kReaderBlock && !reader_block_in_use) {
    if (reader_block == nullptr) {
      reader_block = static_cast<char*>(std::malloc(kReaderBlock));
      if (reader_block == nullptr) throw std::bad_alloc();
    }
    ASAN_UNPOISON_MEMORY_REGION(reader_block, kReaderBlock);
    reader_block_in_use = true;
    return reader_block;
  }
  void* p = std::malloc(size == 0 ? 1 : size);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}

void operator delete[](void* p) noexcept {
  if (p != nullptr && p == reader_block) {
    ASAN_POISON_MEMORY_REGION(reader_block, kReaderBlock);
    reader_block_in_use = false;
    return;
  }
  std::free(p);
}

void operator delete[](void* p, std::size_t) noexcept { operator delete[](p); }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    fit3dof::ParseTimeHistory(text, "fuzz.csv");
  } catch (const fit3dof::InputError&) {
  }
  return 0;
}
