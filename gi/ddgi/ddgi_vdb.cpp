// OpenVDB export of the probe field; kept in its own file so no OpenVDB header leaks out.
#include <openvdb/openvdb.h>

#include "gi/ddgi/ddgi_technique.h"
#include "volumes/nano_geometry_vdb.h"
#include "volumes/openvdb_file.h"

namespace voxgi {

void writeProbeVdb(const ProbeField& field, const std::string& path, const NanoGeometry* traceVolume) {
    openvdb::initialize();
    openvdb::GridPtrVec grids;
    for (std::size_t vi = 0; vi < field.volumes().size(); ++vi) {
        const ProbeVolume& v = field.volumes()[vi];
        std::string suffix = vi == 0 ? "" : "_c" + std::to_string(vi);
        // Index space is the logical probe lattice; the transform puts voxel centres on probes.
        openvdb::math::Transform::Ptr xform = openvdb::math::Transform::createLinearTransform(
            openvdb::math::Mat4d(openvdb::math::Mat4d::identity()));
        xform->preScale(openvdb::Vec3d(v.spacing.x, v.spacing.y, v.spacing.z));
        xform->postTranslate(openvdb::Vec3d(v.origin.x, v.origin.y, v.origin.z));

        auto position = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
        auto offset = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
        auto irradiance = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
        // A float grid: pyopenvdb (python3-openvdb) reads only float, bool and vec3s grids.
        auto state = openvdb::FloatGrid::create(-1.0f);
        auto pa = position->getAccessor();
        auto oa = offset->getAccessor();
        auto ia = irradiance->getAccessor();
        auto sa = state->getAccessor();
        for (int local = 0; local < v.probeCount(); ++local) {
            int probe = v.probeBase + local;
            glm::ivec3 l = v.logicalOf(v.storageFromLocal(local));
            openvdb::Coord c(l.x, l.y, l.z);
            const ProbeRecord& rec = field.probes[std::size_t(probe)];
            glm::vec3 p = field.probePosition(probe);
            glm::vec3 e = field.meanIrradiance(probe);
            pa.setValue(c, openvdb::Vec3s(p.x, p.y, p.z));
            oa.setValue(c, openvdb::Vec3s(rec.offset.x, rec.offset.y, rec.offset.z));
            ia.setValue(c, openvdb::Vec3s(e.x, e.y, e.z));
            sa.setValue(c, float(int(rec.state)));
        }
        auto finish = [&](openvdb::GridBase::Ptr g, const std::string& name, openvdb::GridClass cls) {
            g->setName(name + suffix);
            g->setTransform(xform->copy());
            g->setGridClass(cls);
            g->insertMeta("voxgi_cascade", openvdb::Int32Metadata(int(vi)));
            g->insertMeta("voxgi_cell_size", openvdb::Vec3SMetadata(openvdb::Vec3s(v.spacing.x, v.spacing.y, v.spacing.z)));
            grids.push_back(g);
        };
        finish(position, "probe_position", openvdb::GRID_UNKNOWN);
        finish(offset, "probe_offset", openvdb::GRID_UNKNOWN);
        finish(state, "probe_state", openvdb::GRID_UNKNOWN);
        finish(irradiance, "probe_irradiance", openvdb::GRID_UNKNOWN);
        state->insertMeta("voxgi_states", openvdb::StringMetadata("0 active, 1 sleeping, 2 off"));
        irradiance->insertMeta("voxgi_units", openvdb::StringMetadata("W/m^2, mean over directions"));
    }
    if (traceVolume)
        for (const openvdb::GridBase::Ptr& g : nanoGeometryGrids(*traceVolume, "trace_")) grids.push_back(g);
    writeVdbFile(path, grids);
}

}  // namespace voxgi
