// One number a technique reports about its last frame (rays traced, bricks propagated...), for
// benchmarks and the viewer.
#pragma once

#include <string>

namespace voxgi {

struct TechniqueStat {
    std::string name;
    double value = 0.0;
    std::string unit;  // "ms", "rays", ...
};

}  // namespace voxgi
