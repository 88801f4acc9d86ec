// The host's GL state as the SDK promises to leave it: every binding and setting that the state-preservation tests
// set to sentinels, captured as named integers, and the difference of two captures. Shared by the tests that check
// the state contract (state_preservation_test.cpp) and those that check it on failure paths
// (allocation_failure_test.cpp).
#ifndef OBSCURA_TESTS_GL_STATE_SNAPSHOT_H
#define OBSCURA_TESTS_GL_STATE_SNAPSHOT_H

#include <string>
#include <utility>
#include <vector>

namespace obscura_test {

// How much of each indexed state a snapshot covers.
constexpr int kSnapshotTextureUnits = 8;
constexpr int kSnapshotSamplerUnits = 4;
constexpr int kSnapshotImageUnits = 7;  // the SDK uses 6 (the z pyramid writes six levels) and one beyond
constexpr int kSnapshotBufferIndices = 3;

// Every piece of state the sentinel setup touches, as plain integers, with names for the diff.
struct Snapshot {
    std::vector<std::pair<std::string, long long>> values;
    void add(const std::string& name, long long value) { values.emplace_back(name, value); }
};

// The current context's state.
Snapshot capture();

// Names of the entries that differ, with both values; empty when none does.
std::string diff(const Snapshot& before, const Snapshot& after);

}  // namespace obscura_test

#endif  // OBSCURA_TESTS_GL_STATE_SNAPSHOT_H
