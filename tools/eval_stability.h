// `voxgi eval --stability`: stiff and extreme cases (closed boxes with albedo near 1, 10,000
// propagation steps, light intensities and scene scales over 20 orders of magnitude, degenerate
// and NaN geometry, grazing light, DDGI probes inside walls, hysteresis 0 and 1). Each case
// reports whether the result is finite, its energy ratio to an analytic or invariant value where
// one exists, the largest value, and pass/fail; a case that cannot run says why and never passes.
#pragma once

#include <string>
#include <vector>

namespace voxgi::cli {

struct StabilityResult {
    std::string name, method, description;
    bool ran = false;
    std::string notRunReason;
    bool finite = false;
    double ratio = 0.0;       // NaN when there is no analytic or invariant value to compare with
    std::string expected;     // what the ratio is measured against
    double largest = 0.0;
    bool passed = false;
    double seconds = 0.0;
};

// The case names, in the order they run.
std::vector<std::string> stabilityCaseNames();
// Runs `cases` (all when empty; InputError for an unknown name), writes `dir`/stability.md and
// stability.json, and returns true when no case that ran failed.
bool runStabilitySuite(const std::string& dir, const std::vector<std::string>& cases);
std::vector<StabilityResult> runStabilityCases(const std::vector<std::string>& cases);

}  // namespace voxgi::cli
