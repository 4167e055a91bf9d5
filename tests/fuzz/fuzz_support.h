// Shared by the fuzz targets: a private scratch folder, input splitting, files written whole.
// A target is a libFuzzer entry point (LLVMFuzzerTestOneInput) built two ways: with clang's
// -fsanitize=fuzzer for fuzzing (scripts/fuzz.sh), and with replay_main.cpp for the ctest case
// that replays tests/fuzz/corpus/<target>/ on every CI run.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace terrasynth::fuzz {

// A folder for this process's files (under $TMPDIR or /tmp), created once.
const std::string& scratchDir();
// Writes `bytes` to `path`, replacing it (aborts the process if it cannot: the harness is broken).
void writeFile(const std::string& path, const std::string& bytes);
// Splits an input into two parts: a little-endian u16 length, that many bytes, then the rest (an
// input shorter than the length gives the short part whole and an empty rest).
void splitInput(const uint8_t* data, size_t size, std::string* first, std::string* rest);

}  // namespace terrasynth::fuzz
