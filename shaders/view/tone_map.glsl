// The viewer's display transform: shaders/shared/tone_map.h with the curve the viewer picked.
#include "shared/tone_map.h"
uniform int uToneCurve;  // kToneFilmic or kToneReinhard
vec3 toDisplay(vec3 x) { return displaySrgb(x, 1.0, uToneCurve); }
