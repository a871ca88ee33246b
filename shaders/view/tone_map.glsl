// ACES filmic fit (Narkowicz 2015) then the sRGB transfer: scenes/image.cpp toneMapToSrgb.
vec3 acesSrgb(vec3 x) {
    x = max(x, vec3(0.0));
    x = clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
    return mix(1.055 * pow(x, vec3(1.0 / 2.4)) - 0.055, 12.92 * x, lessThanEqual(x, vec3(0.0031308)));
}
