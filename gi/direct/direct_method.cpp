// `direct`: the frame without a GI technique, direct light and emission only (its indirect
// layer is black). The floor every method is measured against.
#include "gi/method.h"

namespace voxgi {

MethodInfo directMethod() {
    MethodInfo m;
    m.name = "direct";
    m.summary = "baseline: direct light and emission only, no indirect light";
    m.validate = [](const GiSettings&) {};
    m.plan = [](const Scene&) { return TechniquePlan{}; };
    return m;
}

}  // namespace voxgi
