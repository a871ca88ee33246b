// Irradiance from the probe field at a shading point: the 8-probe cage of each volume,
// weighted trilinear x wrap (backface) x Chebyshev visibility x weight crushing, with normal
// and view bias; cascades blend finest first. The CPU reference of shaders/ddgi/sampling.glsl.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gi/ddgi/probe_field.h"

namespace voxgi {

// Chebyshev's upper bound on the chance that a point at distance r from the probe is visible,
// from the distance moments (mean, mean of squares): 1 for r <= mean, 0 when the variance is
// zero and r > mean.
float chebyshevVisibility(float r, float mean, float meanSquare);

// 0 outside, 1 more than one cell inside the volume, linear across the outermost cell.
float volumeBlendWeight(const ProbeVolume& volume, glm::vec3 p);

// How a ProbeSampler evaluates the eight cage probes: the portable reference, or all eight in
// one AVX2 register (x86-64 CPUs with AVX2, detected at run time). Their cage weights are
// identical; the weighted sums differ by rounding (tests/test_ddgi_sampling.cpp).
enum class SamplingPath { Scalar, Avx2 };
bool samplingPathSupported(SamplingPath path);
SamplingPath bestSamplingPath();

// The sampling functions over a snapshot of a field: per-probe positions, states and atlas
// tile addresses are resolved once (in logical probe order, so the cage needs no toroidal
// arithmetic) and the eight cage probes are evaluated lane by lane. Borrows the field, which
// must not change while the sampler is used (ray shading samples the previous frame's field).
class ProbeSampler {
public:
    explicit ProbeSampler(const ProbeField& field) : ProbeSampler(field, bestSamplingPath()) {}
    // Throws std::logic_error when this CPU cannot run `path`.
    ProbeSampler(const ProbeField& field, SamplingPath path);

    // Irradiance (W/m^2) at p for unit normal n, seen from unit direction `toViewer`. Zero
    // where no probe contributes (every cage probe off).
    glm::vec3 irradiance(glm::vec3 p, glm::vec3 n, glm::vec3 toViewer) const;
    // One volume only; `weightSum` receives the sum of its probe weights.
    glm::vec3 volumeIrradiance(int volume, glm::vec3 p, glm::vec3 n, glm::vec3 toViewer, float* weightSum) const;
    // Occlusion probes (seed 004 ch. 5): visibility of up to four lights (one per channel) at
    // p, from the occlusion atlas with the same cage weights, looked up in the direction from
    // each probe to p. All ones without an occlusion atlas.
    glm::vec4 occlusion(glm::vec3 p, glm::vec3 n) const;

    const ProbeField& field() const { return field_; }
    SamplingPath path() const { return path_; }

private:
    struct CageProbe {
        glm::vec3 position{0.0f};   // relocated world position
        float live = 0.0f;          // 0 for off probes
        std::uint32_t distanceTexel = 0;    // first texel of the tile in the distance atlas
        std::uint32_t irradianceTexel = 0;  // ... in the irradiance atlas
    };
    struct Volume {
        glm::ivec3 counts{1};
        glm::vec3 origin{0.0f}, spacing{1.0f};
        float biasScale = 1.0f;  // smallest spacing
        int first = 0;           // first CageProbe of the volume
        // Cage corner c relative to the base probe, and 0 where it lies outside the volume (a
        // dimension of one probe), where it then repeats its inside neighbour.
        int cornerOffset[8] = {};
        float cornerInside[8] = {};
    };
    template <bool kOcclusion>
    glm::vec4 gather(const Volume& v, glm::vec3 p, glm::vec3 n, glm::vec3 toViewer, float* weightSum) const;
    // gather on eight AVX2 lanes (probe_sampling_avx2.cpp); call only where the CPU has AVX2.
    template <bool kOcclusion>
    glm::vec4 gatherAvx2(const Volume& v, glm::vec3 p, glm::vec3 n, glm::vec3 toViewer, float* weightSum) const;

    const ProbeField& field_;
    std::vector<Volume> volumes_;
    std::vector<CageProbe> probes_;
    SamplingPath path_ = SamplingPath::Scalar;
};

// One-off lookups (build a sampler per call: O(probes); use a ProbeSampler for many points).
glm::vec3 sampleIrradiance(const ProbeField& field, glm::vec3 p, glm::vec3 n, glm::vec3 toViewer);
glm::vec3 sampleVolumeIrradiance(const ProbeField& field, int volume, glm::vec3 p, glm::vec3 n, glm::vec3 toViewer,
                                 float* weightSum = nullptr);
glm::vec4 sampleOcclusion(const ProbeField& field, glm::vec3 p, glm::vec3 n);

}  // namespace voxgi
