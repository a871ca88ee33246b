#include "gi/raytrace/triangle_bvh.h"

#include <cmath>
#include <cstring>
#include <new>
#include <stdexcept>
#include <string>

#include <embree3/rtcore.h>

#include "scenes/memory_limit.h"
#include "scenes/scene.h"

namespace voxgi {

namespace {

constexpr unsigned kMaxLeafTriangles = 4;
constexpr unsigned kMaxDepth = 48;  // the GPU traversal's stack holds this many nodes

struct BuildNode {
    bool leaf = false;
};
struct InnerNode : BuildNode {
    BuildNode* child[2] = {nullptr, nullptr};
    RTCBounds bounds[2] = {};
};
struct LeafNode : BuildNode {
    unsigned count = 0;
    unsigned triangles[kMaxLeafTriangles] = {};
};

void* createInner(RTCThreadLocalAllocator alloc, unsigned, void*) {
    return new (rtcThreadLocalAlloc(alloc, sizeof(InnerNode), 16)) InnerNode();
}
void setChildren(void* node, void** children, unsigned count, void*) {
    for (unsigned i = 0; i < count && i < 2; ++i) static_cast<InnerNode*>(node)->child[i] = static_cast<BuildNode*>(children[i]);
}
void setBounds(void* node, const RTCBounds** bounds, unsigned count, void*) {
    for (unsigned i = 0; i < count && i < 2; ++i) static_cast<InnerNode*>(node)->bounds[i] = *bounds[i];
}
void* createLeaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* prims, size_t count, void*) {
    auto* leaf = new (rtcThreadLocalAlloc(alloc, sizeof(LeafNode), 16)) LeafNode();
    leaf->leaf = true;
    leaf->count = unsigned(count < kMaxLeafTriangles ? count : kMaxLeafTriangles);
    for (unsigned i = 0; i < leaf->count; ++i) leaf->triangles[i] = prims[i].primID;
    return leaf;
}

glm::vec4 withBits(glm::vec3 v, int bits) {
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return glm::vec4(v, f);
}

// Lays the built tree out depth first: each inner node's two children sit in its own record.
class Flattener {
public:
    Flattener(const std::vector<glm::vec3>& corners, TriangleBvh& out) : corners_(corners), out_(out) {}

    int inner(const InnerNode& node) {
        const int index = int(out_.nodeCount());
        out_.nodes.resize(out_.nodes.size() + 4);
        for (int c = 0; c < 2; ++c) {
            const RTCBounds& b = node.bounds[c];
            setChild(index, c, node.child[c], glm::vec3(b.lower_x, b.lower_y, b.lower_z), glm::vec3(b.upper_x, b.upper_y, b.upper_z));
        }
        return index;
    }

    void setChild(int index, int c, const BuildNode* child, glm::vec3 lo, glm::vec3 hi) {
        int first = -1, count = 0;
        if (child && child->leaf) {
            const auto& leaf = *static_cast<const LeafNode*>(child);
            first = int(out_.triangle.size());
            count = int(leaf.count);
            for (unsigned i = 0; i < leaf.count; ++i) {
                const unsigned t = leaf.triangles[i];
                out_.triangle.push_back(t);
                for (int k = 0; k < 3; ++k) out_.corners.emplace_back(corners_[3 * std::size_t(t) + std::size_t(k)], 0.0f);
            }
        } else if (child) {
            first = inner(*static_cast<const InnerNode*>(child));
        }
        // (inner() may have grown the vector: index, not a pointer.)
        out_.nodes[std::size_t(4 * index + 2 * c)] = withBits(lo, first);
        out_.nodes[std::size_t(4 * index + 2 * c + 1)] = withBits(hi, count);
    }

private:
    const std::vector<glm::vec3>& corners_;
    TriangleBvh& out_;
};

}  // namespace

double triangleBvhBytes(std::size_t triangles) {
    // Build primitives 32 B, corners 36 B, Embree's nodes and leaves about 80 B, the layout
    // 52 B (corners) + 4 B (index) + about 32 B of nodes, per triangle.
    return 240.0 * double(triangles);
}

TriangleBvh buildTriangleBvh(const Scene& scene) {
    std::size_t total = 0;
    for (const Mesh& m : scene.meshes) total += m.triangleCount();
    requireMemory(triangleBvhBytes(total), "triangle BVH of " + std::to_string(total) + " triangles");
    std::vector<glm::vec3> corners;
    corners.reserve(3 * total);
    std::vector<RTCBuildPrimitive> prims;
    prims.reserve(total);
    for (const Mesh& mesh : scene.meshes)
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
            const std::uint32_t index = std::uint32_t(corners.size() / 3);
            glm::vec3 p[3];
            for (int k = 0; k < 3; ++k) corners.push_back(p[k] = mesh.positions[mesh.indices[3 * t + std::size_t(k)]]);
            const glm::vec3 lo = glm::min(p[0], glm::min(p[1], p[2])), hi = glm::max(p[0], glm::max(p[1], p[2]));
            // Degenerate and non-finite triangles are never hit: left out, as Embree's scene does.
            const float area = glm::length(glm::cross(p[1] - p[0], p[2] - p[0]));
            if (!(area > 0.0f) || !std::isfinite(area) || !std::isfinite(lo.x + lo.y + lo.z + hi.x + hi.y + hi.z)) continue;
            RTCBuildPrimitive b;
            b.lower_x = lo.x, b.lower_y = lo.y, b.lower_z = lo.z, b.geomID = 0;
            b.upper_x = hi.x, b.upper_y = hi.y, b.upper_z = hi.z, b.primID = index;
            prims.push_back(b);
        }

    TriangleBvh out;
    Flattener flatten(corners, out);
    out.nodes.resize(4);
    if (prims.empty()) {
        flatten.setChild(0, 0, nullptr, glm::vec3(0.0f), glm::vec3(0.0f));
        flatten.setChild(0, 1, nullptr, glm::vec3(0.0f), glm::vec3(0.0f));
        return out;
    }
    RTCDevice device = rtcNewDevice(nullptr);
    if (!device) throw std::runtime_error("cannot create an Embree device");
    RTCBVH bvh = rtcNewBVH(device);
    RTCBuildArguments args = rtcDefaultBuildArguments();
    args.byteSize = sizeof(args);
    args.buildQuality = RTC_BUILD_QUALITY_MEDIUM;  // binned SAH; HIGH (spatial splits) duplicates triangles
    args.maxBranchingFactor = 2;
    args.maxDepth = kMaxDepth;
    args.sahBlockSize = 1;
    args.minLeafSize = 1;
    args.maxLeafSize = kMaxLeafTriangles;
    args.traversalCost = 1.0f;
    args.intersectionCost = 1.0f;
    args.bvh = bvh;
    args.primitives = prims.data();
    args.primitiveCount = prims.size();
    args.primitiveArrayCapacity = prims.size();
    args.createNode = createInner;
    args.setNodeChildren = setChildren;
    args.setNodeBounds = setBounds;
    args.createLeaf = createLeaf;
    const auto* root = static_cast<const BuildNode*>(rtcBuildBVH(&args));
    if (!root) {
        rtcReleaseBVH(bvh);
        rtcReleaseDevice(device);
        throw std::runtime_error("Embree could not build the triangle BVH");
    }
    out.nodes.clear();
    if (root->leaf) {  // a few triangles: the root holds one leaf
        glm::vec3 lo(INFINITY), hi(-INFINITY);
        for (const RTCBuildPrimitive& b : prims) {
            lo = glm::min(lo, glm::vec3(b.lower_x, b.lower_y, b.lower_z));
            hi = glm::max(hi, glm::vec3(b.upper_x, b.upper_y, b.upper_z));
        }
        out.nodes.resize(4);
        flatten.setChild(0, 0, root, lo, hi);
        flatten.setChild(0, 1, nullptr, glm::vec3(0.0f), glm::vec3(0.0f));
    } else {
        flatten.inner(*static_cast<const InnerNode*>(root));
    }
    rtcReleaseBVH(bvh);
    rtcReleaseDevice(device);
    return out;
}

}  // namespace voxgi
