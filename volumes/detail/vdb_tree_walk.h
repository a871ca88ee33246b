// A grid's tree walked before OpenVDB reads it (vdb_structure.cpp calls it). OpenVDB 10.0 takes
// every size inside a tree as written: a chunk stored "uncompressed" with a larger size than
// its node is read past the node's buffer (a heap overflow), a compressed chunk's size is
// allocated as stated (8e18 bytes), and blosc decodes as many bytes as a chunk's own header
// claims. The walk follows OpenVDB's layout for trees of 5-4-3 nodes (format version 222 and
// later: tree/RootNode.h, InternalNode.h, LeafNode*.h and io/Compression.h, readCompressedValues)
// and checks that each of those sizes is the one the node implies.
#pragma once

#include <cstdint>

#include "volumes/detail/vdb_fields.h"

namespace voxgi::detail {

// What the walk needs to know of a grid's tree.
struct VdbTreeLayout {
    enum class Leaves { Values, Bool, Mask };
    std::uint64_t valueBytes = 0;  // a value in the root and in node metadata
    std::uint64_t chunkValueBytes = 0;  // a value in a chunk (half floats when saved as half)
    Leaves leaves = Leaves::Values;
    std::uint32_t compression = 0;  // the grid's compression flags (io/Compression.h)
};

// From just after the root's tile and child counts to the end of the grid's leaf buffers: the
// tiles, every child's masks and compressed values, then every leaf's buffer, which OpenVDB
// reads right after the topology: there the grid's `block` position must point (`block` past
// the file's end: a streamed file, which has none). The walk must end by `end`.
void walkVdbTree(VdbFields& f, const VdbTreeLayout& tree, std::uint32_t tiles, std::uint32_t children,
                 std::uint64_t block, std::uint64_t end);

}  // namespace voxgi::detail
