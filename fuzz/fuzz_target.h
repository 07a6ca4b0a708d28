#pragma once
// The libFuzzer entry point every fuzz_*.cpp defines. Built two ways
// (fuzz/CMakeLists.txt): with clang's -fsanitize=fuzzer for `scripts/hs
// fuzz`, and with replay_main.cpp in the normal build, where ctest runs it
// over the committed corpus and crash reproducers.
#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);
