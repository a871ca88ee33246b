#include "gi/lpv/gl_ordinates.h"

#include <algorithm>
#include <cstdint>

#include "gl/program.h"

namespace voxgi {

namespace {

template <typename T>
void upload(gl::Handle& buffer, std::size_t& capacity, const std::vector<T>& data) {
    gl::ensureBuffer(buffer, capacity, data.size() * sizeof(T));
    if (!data.empty()) glNamedBufferSubData(buffer.id(), 0, GLsizeiptr(data.size() * sizeof(T)), data.data());
}

void zero(gl::Handle& buffer, std::size_t& capacity, std::size_t bytes, double growth = 2.0) {
    gl::ensureBuffer(buffer, capacity, bytes, growth);
    glClearNamedBufferData(buffer.id(), GL_R32F, GL_RED, GL_FLOAT, nullptr);
}

}  // namespace

struct GlOrdinates::Impl {
    gl::Program sweep = gl::Program::compute("lpv/ordinates_sweep.comp");
    gl::Program reflect = gl::Program::compute("lpv/ordinates_reflect.comp");
    gl::Program resolve = gl::Program::compute("lpv/ordinates_resolve.comp");
    // Buffers and their capacities (bytes), by binding.
    gl::Handle taps, surfaceOf, surfaces, sources, parts[2], irradiance, reflected, planeShares, faceShares, power;
    std::size_t tapsCap = 0, surfaceOfCap = 0, surfacesCap = 0, sourcesCap = 0, partsCap[2] = {0, 0}, irradianceCap = 0,
                reflectedCap = 0, planeCap = 0, faceCap = 0, powerCap = 0;
    std::uint64_t uploadedRevision = 0;  // the transport geometry the buffers hold (0: none)
};

GlOrdinates::GlOrdinates() : impl_(new Impl) {}
GlOrdinates::~GlOrdinates() { delete impl_; }

int GlOrdinates::solve(const OrdinatesTransport& t, const OrdinatesTransport::Sources& sources, bool occlusion,
                       int maxBounces, GLuint pool, std::size_t firstSlot) {
    Impl& m = *impl_;
    const CascadeGrid& grid = t.grid();
    const int n = grid.resolution;
    const std::vector<OrdinateBin>& bins = t.bins();
    const BrickMap& bricks = t.bricks();
    const std::size_t nb = bins.size(), surfaces = t.coverage().size(), slots = bricks.slots(),
                      values = bricks.valueCount();
    const std::size_t row = std::size_t(n) + 2, plane = row * row;

    // The bins and surfaces go up when they differ from the last solve's (a cascade's ring and
    // inner light are solved one after the other through the same transport).
    if (t.geometryRevision() != m.uploadedRevision) {
        std::vector<glm::vec4> taps;
        for (const OrdinateBin& b : bins) {
            taps.push_back(glm::vec4(b.taps[0], b.taps[1], b.taps[2], b.taps[3]));
            taps.push_back(glm::vec4(float(b.lateralStep.x), float(b.lateralStep.y), 0.0f, 0.0f));
        }
        upload(m.taps, m.tapsCap, taps);
        // The brick table, then each slot's cells' surface indices: one buffer, so the sweep binds
        // eight (GL's least guaranteed number of storage blocks in a compute shader).
        std::vector<int> surfaceOf = bricks.table();
        surfaceOf.insert(surfaceOf.end(), t.surfaceOfBrickCells().begin(), t.surfaceOfBrickCells().end());
        upload(m.surfaceOf, m.surfaceOfCap, surfaceOf);
        std::vector<glm::vec4> surf(std::max<std::size_t>(3 * surfaces, 3));
        for (std::size_t s = 0; s < surfaces; ++s) {
            surf[3 * s] = glm::vec4(t.vectorCoverage()[s], 0.0f);
            surf[3 * s + 1] = glm::vec4(t.clutterShadow(s), 0.0f);
            surf[3 * s + 2] = glm::vec4(t.albedo()[s], 0.0f);
        }
        upload(m.surfaces, m.surfacesCap, surf);
        std::vector<float> planeShares = t.planeReflectionShares();
        planeShares.resize(std::max<std::size_t>(planeShares.size(), nb), -1.0f);
        upload(m.planeShares, m.planeCap, planeShares);
        std::vector<float> faces;
        for (const std::vector<float>& f : t.faceReflectionShares()) faces.insert(faces.end(), f.begin(), f.end());
        upload(m.faceShares, m.faceCap, faces);
        m.uploadedRevision = t.geometryRevision();
    }
    std::vector<float> source = t.binMajor(sources);
    source.resize(std::max<std::size_t>(source.size(), 3), 0.0f);
    upload(m.sources, m.sourcesCap, source);
    // The stored bricks' cells by axis group: the largest buffer here, sized to them.
    zero(m.irradiance, m.irradianceCap, std::max<std::size_t>(3 * values, 1) * sizeof(glm::vec4), 1.0);
    zero(m.reflected, m.reflectedCap, std::max<std::size_t>(3 * surfaces * kOrdinateFaces, 1) * sizeof(glm::vec4));
    const std::size_t groups = (std::max<std::size_t>(surfaces, 1) + 63) / 64;
    zero(m.power, m.powerCap, groups * sizeof(float));

    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, m.taps.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, m.surfaceOf.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, m.surfaces.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, m.sources.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, m.irradiance.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, m.reflected.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, m.planeShares.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 9, m.faceShares.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 10, m.power.id());
    m.sweep.set("uN", n);
    m.sweep.set("uTableSide", bricks.tableSide());
    m.sweep.set("uBrickCellsStart", int(bricks.tableSize()));
    m.sweep.set("uSlots", int(slots));
    m.sweep.set("uBinsPerPyramid", int(nb / 6));
    m.sweep.set("uSurfaces", int(surfaces));
    m.sweep.set("uOcclusion", occlusion ? 1 : 0);
    m.sweep.set("uPerArea", 1.0f / (grid.cellSize * grid.cellSize));
    m.reflect.set("uSurfaces", int(surfaces));
    m.reflect.set("uBins", int(nb));
    m.reflect.set("uClear", 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);

    // Only the sweep box (OrdinatesTransport::sweepBox): each pyramid steps through its axis's
    // slabs of it, each invocation one lateral cell of it.
    const IndexBox box = t.sweepBox();
    const glm::ivec3 extent = box.max - box.min + 1;
    m.sweep.set("uBoxMin", box.min);
    m.sweep.set("uBoxMax", box.max);
    double carried = sources.watts;
    int sweeps = 0;
    const int longest = std::max({extent.x, extent.y, extent.z});  // slabs and lateral cells
    const GLuint lateral = GLuint((longest + 7) / 8);
    for (int bounce = 0; bounce < maxBounces && carried > 0.0 && !box.empty(); ++bounce) {
        // Each sweep starts from zero power in every slab (and the border stays zero).
        for (int i = 0; i < 2; ++i) zero(m.parts[i], m.partsCap[i], nb * plane * 4 * sizeof(glm::vec4));
        m.sweep.use();
        for (int step = 0; step < longest; ++step) {
            m.sweep.set("uStep", step);
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, m.parts[step % 2].id());
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, m.parts[(step + 1) % 2].id());
            // Where an axis's +axis and -axis pyramids reach the same (middle) plane, both would add
            // to its cells' side faces and reflections in one dispatch: one sign after the other.
            bool meet = false;
            for (int a = 0; a < 3; ++a) meet = meet || box.max[a] - box.min[a] == 2 * step;
            const int signs[2] = {meet ? 1 : 3, 2};
            for (int pass = 0; pass < (meet ? 2 : 1); ++pass) {
                m.sweep.set("uSigns", signs[pass]);
                glDispatchCompute(lateral, lateral, 6);
                glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
            }
        }
        ++sweeps;
        m.reflect.use();
        glDispatchCompute(GLuint(groups), 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        std::vector<float> partial(groups);
        glGetNamedBufferSubData(m.power.id(), 0, GLsizeiptr(groups * sizeof(float)), partial.data());
        carried = 0.0;
        for (float p : partial) carried += double(p);
        if (carried < kOrdinatesConverged * sources.watts) break;
    }
    if (slots > 0) {
        m.resolve.use();
        m.resolve.set("uSlots", int(slots));
        m.resolve.set("uFirstSlot", int(firstSlot));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 12, pool);
        glDispatchCompute(GLuint(kOrdinateFaces), GLuint(slots), 1);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    return sweeps;
}

IrradianceBricks readBricks(GLuint pool, std::size_t firstSlot, std::size_t slots) {
    constexpr std::size_t perSlot = BrickMap::kSlotValues;
    IrradianceBricks out(slots * perSlot);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    if (!out.empty())
        glGetNamedBufferSubData(pool, GLintptr(firstSlot * perSlot * sizeof(glm::vec4)),
                                GLsizeiptr(out.size() * sizeof(glm::vec4)), out.data());
    return out;
}

}  // namespace voxgi
