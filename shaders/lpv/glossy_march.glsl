// Glossy reflections from the finest cascade (seed 000 section 3.10.4), for both transports'
// apply passes: march along the reflected ray one cell per step and average the radiance
// arriving back along it with 1/d^2 weights, over the cells the volume stores (the ordinates
// keep bricks around surfaces only). Included after the cascade uniforms (uCellSize); the
// including shader defines glossyCellRadiance.
uniform float uTracedRoughness;
uniform vec3 uEye;
uniform int uGlossy;

// Radiance (W/m^2/sr) arriving at uvw of cascade 0 from direction r (rgb); a: 1 where the volume
// stores it, 0 where not.
vec4 glossyCellRadiance(vec3 uvw, vec3 r);

vec3 glossyRadiance(vec3 p, vec3 r, float roughness) {
    int steps = int(mix(12.0, 4.0, clamp(roughness, 0.0, 1.0)));
    vec3 sum = vec3(0.0);
    float weights = 0.0;
    for (int i = 1; i <= steps; ++i) {
        vec3 q = p + r * (float(i) * uCellSize[0]);
        if (cascadeInlier(0, q) <= 0.0) break;
        vec4 radiance = glossyCellRadiance(uvwOf(0, q), r);
        float w = radiance.a / (float(i) * float(i));
        sum += max(radiance.rgb, vec3(0.0)) * w;
        weights += w;
    }
    return weights > 0.0 ? sum / weights : vec3(0.0);
}

// Schlick-Fresnel times the march, for specular or metallic surfaces smoother than 0.6 whose
// lobe the hybrid method's rays do not trace (uTracedRoughness).
vec3 glossyReflection(GBufferSurface s) {
    vec3 f0 = mix(vec3(s.specular), s.albedo, s.metallic);
    bool traced = tracedLobe(s.roughness, s.metallic, s.specular, s.transmission, uTracedRoughness);
    if (uGlossy == 0 || traced || max(f0.r, max(f0.g, f0.b)) <= 0.0 || s.roughness >= 0.6) return vec3(0.0);
    vec3 n = s.normal;
    vec3 v = normalize(uEye - s.position);
    vec3 r = reflect(-v, n);
    vec3 fresnel = f0 + (1.0 - f0) * pow(1.0 - max(dot(n, v), 0.0), 5.0);
    return (1.0 - s.transmission) * fresnel * glossyRadiance(s.position + n * (0.5 * uCellSize[0]), r, s.roughness);
}
