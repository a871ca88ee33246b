#include "gi/ddgi/probe_states.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "shaders/shared/probe_schedule.h"

namespace voxgi {

static_assert(int(ProbeState::Active) == shading::kProbeActive && int(ProbeState::Sleeping) == shading::kProbeSleeping &&
              int(ProbeState::Off) == shading::kProbeOff);
static_assert(int(ProbeWork::None) == shading::kProbeWorkNone && int(ProbeWork::FixedOnly) == shading::kProbeWorkFixedOnly &&
              int(ProbeWork::Full) == shading::kProbeWorkFull);

std::vector<ProbeWork> scheduleProbes(const ProbeField& field, std::uint32_t frame, bool occupancyKnown) {
    const DdgiDesc& desc = field.desc();
    std::vector<ProbeWork> work(std::size_t(field.probeCount()), ProbeWork::Full);
    for (int p = 0; p < field.probeCount(); ++p) {
        const ProbeRecord& rec = field.probes[std::size_t(p)];
        work[std::size_t(p)] = ProbeWork(shading::probeWork(desc.classify, int(rec.state), rec.blends, int(frame), p,
                                                            desc.sleepInterval, occupancyKnown));
    }
    return work;
}

void relocateProbes(ProbeField& field, const RaySet& rays, const ProbeTrace& trace) {
    const DdgiDesc& desc = field.desc();
    tbb::parallel_for(tbb::blocked_range<int>(0, field.probeCount()), [&](const tbb::blocked_range<int>& r) {
        for (int p = r.begin(); p != r.end(); ++p) {
            if (trace.work[std::size_t(p)] != ProbeWork::Full) continue;
            const ProbeVolume& v = field.volumes()[std::size_t(field.volumeOf(p))];
            const float minFront = desc.minFrontfaceDistance * v.minSpacing();
            shading::ProbeHits hits;
            hits.traced = trace.blendRaysTraced ? trace.stride : rays.fixedRays;
            if (hits.traced == 0) continue;
            hits.backfaces = 0;
            hits.closestBack = hits.closestFront = INFINITY;
            hits.closestBackDir = hits.closestFrontDir = glm::vec3(0.0f);
            for (int i = 0; i < hits.traced; ++i) {
                float d = trace.at(p, i).distance;
                const glm::vec3& dir = rays.directions[std::size_t(i)];
                if (d < 0.0f) {
                    ++hits.backfaces;
                    if (-d < hits.closestBack) hits.closestBack = -d, hits.closestBackDir = dir;
                } else if (d < hits.closestFront) {
                    hits.closestFront = d, hits.closestFrontDir = dir;
                }
            }
            ProbeRecord& rec = field.probes[std::size_t(p)];
            rec.offset = shading::relocatedOffset(rec.offset, hits, desc.relocationBackfaceThreshold, minFront, v.spacing);
        }
    });
}

void classifyProbes(ProbeField& field, const RaySet& rays, const ProbeTrace& trace, const GeometryQuery& query) {
    const DdgiDesc& desc = field.desc();
    if (!desc.classify || rays.fixedRays == 0) return;
    tbb::parallel_for(tbb::blocked_range<int>(0, field.probeCount()), [&](const tbb::blocked_range<int>& r) {
        for (int p = r.begin(); p != r.end(); ++p) {
            if (trace.work[std::size_t(p)] == ProbeWork::None) continue;
            const ProbeVolume& v = field.volumes()[std::size_t(field.volumeOf(p))];
            glm::vec3 position = field.probePosition(p);
            int backfaces = 0;
            bool near = false;
            for (int i = 0; i < rays.fixedRays; ++i) {
                const ProbeSurfel& s = trace.at(p, i);
                if (s.distance < 0.0f) {
                    ++backfaces;
                } else if (s.distance < kMissDistance) {
                    near |= glm::all(glm::lessThanEqual(glm::abs(trace.position(rays, p, i) - position), v.spacing));
                }
            }
            bool inside = float(backfaces) / float(rays.fixedRays) > desc.backfaceThreshold;
            if (query.insideSolid && query.insideSolid(position)) inside = true;
            if (query.distanceToGeometry && query.distanceToGeometry(position) <= v.cellDiagonal()) near = true;
            ProbeRecord& rec = field.probes[std::size_t(p)];
            const ProbeState next = ProbeState(shading::classifiedState(inside, near));
            if (rec.state == ProbeState::Off && next != ProbeState::Off) rec.blends = 0;
            rec.state = next;
        }
    });
}

ProbeStateCounts countStates(const ProbeField& field) {
    ProbeStateCounts c;
    for (const ProbeRecord& r : field.probes) {
        if (r.state == ProbeState::Active) ++c.active;
        else if (r.state == ProbeState::Sleeping) ++c.sleeping;
        else ++c.off;
    }
    return c;
}

}  // namespace voxgi
