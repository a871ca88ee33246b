// The octahedral mapping and tile borders shared by the DDGI atlases, and the atlases' layout.
#include <gtest/gtest.h>

#include "gi/ddgi/probe_field.h"
#include "gi/octahedral/octahedral.h"
#include "gi/sampling/sequences.h"
#include "shaders/shared/constants.h"

using namespace voxgi;

TEST(Octahedral, EncodeDecodeRoundTrip) {
    for (int i = 0; i < 2000; ++i) {
        glm::vec3 d = sphericalFibonacci(i, 2000);
        glm::vec2 s = oct::encode(d);
        EXPECT_LE(std::abs(s.x) + 0.0f, 1.0f);
        EXPECT_LE(std::abs(s.y) + 0.0f, 1.0f);
        EXPECT_LT(glm::length(oct::decode(s) - d), 1e-5f) << i;
    }
    // Poles and axes.
    for (glm::vec3 d : {glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::vec3(1, 0, 0), glm::vec3(0, -1, 0)})
        EXPECT_LT(glm::length(oct::decode(oct::encode(d)) - d), 1e-6f);
}

TEST(Octahedral, BorderTexelsContinueTheSphere) {
    for (int n : {2, 8, 16}) {
        // A border texel sits half a texel outside the edge; the texel it copies must be the
        // interior texel nearest to that outside point on the sphere.
        float texelAngle = shading::kPi / float(n);
        for (int y = 0; y < n + 2; ++y)
            for (int x = 0; x < n + 2; ++x) {
                glm::ivec2 s = oct::borderSource(x, y, n);
                ASSERT_GE(s.x, 1);
                ASSERT_LE(s.x, n);
                ASSERT_GE(s.y, 1);
                ASSERT_LE(s.y, n);
                bool interior = x >= 1 && y >= 1 && x <= n && y <= n;
                if (interior) {
                    EXPECT_EQ(s, glm::ivec2(x, y));
                    continue;
                }
                // Its in-tile neighbour (clamped inside) and the source are near on the sphere.
                glm::ivec2 inner = glm::clamp(glm::ivec2(x, y), glm::ivec2(1), glm::ivec2(n));
                glm::vec3 a = oct::texelDirection(inner.x - 1, inner.y - 1, n);
                glm::vec3 b = oct::texelDirection(s.x - 1, s.y - 1, n);
                EXPECT_LT(std::acos(std::min(1.0f, glm::dot(a, b))), 2.5f * texelAngle) << n << " " << x << "," << y;
            }
    }
}

TEST(Octahedral, TileCoordinatesStayInsideTheBorder) {
    for (int i = 0; i < 500; ++i) {
        glm::vec2 c = oct::tileCoordinate(sphericalFibonacci(i, 500), 8);
        EXPECT_GE(c.x, 1.0f);
        EXPECT_LE(c.x, 9.0f);
        EXPECT_GE(c.y, 1.0f);
        EXPECT_LE(c.y, 9.0f);
    }
}

TEST(Octahedral, AtlasRowsMatchTheTiledLayout) {
    // The GL textures are row-major, the CPU atlas tile-major: toRows / fromRows move whole
    // tile rows, and must put every texel where at(x, y) has it.
    Atlas atlas;
    atlas.resize(5, 3, 6, glm::vec4(0.0f));
    for (int y = 0; y < atlas.height; ++y)
        for (int x = 0; x < atlas.width; ++x) atlas.at(x, y) = glm::vec4(float(x), float(y), float(x * 1000 + y), 1.0f);
    std::vector<glm::vec4> rows;
    atlas.toRows(rows);
    ASSERT_EQ(rows.size(), std::size_t(atlas.width * atlas.height));
    for (int y = 0; y < atlas.height; ++y)
        for (int x = 0; x < atlas.width; ++x) ASSERT_EQ(rows[std::size_t(y * atlas.width + x)], atlas.at(x, y));
    for (glm::vec4& t : rows) t.w = 2.0f;
    atlas.fromRows(rows);
    for (int y = 0; y < atlas.height; ++y)
        for (int x = 0; x < atlas.width; ++x)
            ASSERT_EQ(atlas.at(x, y), glm::vec4(float(x), float(y), float(x * 1000 + y), 2.0f));
}
