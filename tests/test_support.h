// Helpers shared by the tests: where the data lives, scratch paths, small real-data crops.
#pragma once

#include <string>

#include "terrasynth/heightfield.h"

namespace terrasynth::test {

std::string dataDir();             // shipped defaults: <repo>/data
std::string sharedExemplarsDir();  // ../shared/exemplars
std::string binDir();              // built executables
// Runs `<binDir>/terrasynth <args>` through the shell; stdout and stderr together.
struct CliRun {
    int exit_code = -1;
    std::string out;
};
CliRun runTerrasynth(const std::string& args);
bool terrasynthBuilt();
// A fresh, empty scratch directory for one test: <build>/test_tmp/<name>.
std::string scratchDir(const std::string& name);
// <build>/test_tmp/<name>, left as it is (for caches that outlive one run).
std::string tmpPath(const std::string& name);
// Loads a shipped or shared exemplar (by stem, e.g. "orom_alaska") and aborts the test on error.
Heightfield loadExemplarField(const std::string& stem);
// Crop of a field (x0,y0,w,h), same spacing.
Heightfield crop(const Heightfield& field, int x0, int y0, int w, int h);

}  // namespace terrasynth::test

#include <memory>

#include "terrasynth/database.h"

namespace terrasynth::test {
// The database of the shipped default exemplars, built once and cached in the build tree
// (<build>/test_tmp/default.tsdb, rebuilt when stale) so test executables share it.
std::shared_ptr<const ExemplarDatabase> defaultDatabase();
// Where defaultDatabase() keeps its cache file (valid once defaultDatabase() has been called).
std::string defaultDatabasePath();
}  // namespace terrasynth::test
