// Self-illumination of an infinite sunlit plane under the LPV's 5-face propagation (the scheme
// of gi/lpv/propagation.h: face solid angles, point evaluation toward each face centre,
// re-emission as a unit-flux cosine lobe about the face normal), with 2- or 3-band SH; periodic
// in x and z, the floor at y = 0 a perfect blocker without bounces, open above. Prints the
// irradiance the floor reads back from the cell above it (the apply pass's lookup half a cell
// up, cosine-convolved toward -n) over its own exitance, which is 0 for real light.
// Standalone, not built with voxgi (docs/lpv.md, self-illumination):
//   g++ -O2 -o /tmp/selfillum docs/experiments/lpv_self_illumination.cpp
//   /tmp/selfillum 4 64; /tmp/selfillum 9 64   (SH coefficients, steps)
//   CENTRAL=1 /tmp/selfillum 4 64              (re-emit along each face's central direction)
#include <cmath>
#include <cstdio>
#include <vector>
#include <array>
#include <cstdlib>
#include <algorithm>
#include <glm/glm.hpp>
using namespace glm;
const double PI = 3.14159265358979;
int NB;  // number of SH coefficients (4 or 9)
void basis(dvec3 w, double* y) {
    y[0] = 0.282094792;
    y[1] = -0.488602512 * w.y; y[2] = 0.488602512 * w.z; y[3] = -0.488602512 * w.x;
    if (NB > 4) {
        y[4] = 1.092548431 * w.x * w.y; y[5] = -1.092548431 * w.y * w.z; y[6] = 0.315391565 * (3 * w.z * w.z - 1);
        y[7] = -1.092548431 * w.x * w.z; y[8] = 0.546274215 * (w.x * w.x - w.y * w.y);
    }
}
int band(int i) { return i == 0 ? 0 : (i < 4 ? 1 : 2); }
// unit-flux clamped cosine about n
void lobe(dvec3 n, double* c) {
    double y[9]; basis(n, y);
    const double z[3] = {std::sqrt(PI) / 2, std::sqrt(PI / 3), std::sqrt(5 * PI) / 8};
    for (int i = 0; i < NB; ++i) { int l = band(i); c[i] = std::sqrt(4 * PI / (2 * l + 1)) * z[l] * y[i] / PI; }
}
double eval(const double* c, dvec3 w) { double y[9]; basis(w, y); double s = 0; for (int i = 0; i < NB; ++i) s += c[i] * y[i]; return s; }
double convolveCos(const double* c, dvec3 n) {
    const double A[3] = {PI, 2 * PI / 3, PI / 4};
    double y[9]; basis(n, y); double s = 0; for (int i = 0; i < NB; ++i) s += A[band(i)] * c[i] * y[i]; return s;
}
double solidAngle(dvec3 eye, std::vector<dvec3> q) {
    double t = 0;
    for (size_t i = 1; i + 1 < q.size(); ++i) {
        dvec3 a = q[0] - eye, b = q[i] - eye, c = q[i + 1] - eye;
        double la = length(a), lb = length(b), lc = length(c);
        t += 2 * std::atan2(std::abs(dot(a, cross(b, c))), la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la);
    }
    return t;
}
int main(int argc, char** argv) {
    NB = argc > 1 ? std::atoi(argv[1]) : 4;
    int maxSteps = argc > 2 ? std::atoi(argv[2]) : 64;
    const int P = 8, H = 80;
    ivec3 axes[6] = {{1,0,0},{-1,0,0},{0,1,0},{0,-1,0},{0,0,1},{0,0,-1}};
    struct Face { dvec3 dir; double omega; double lobe[9]; };
    Face faces[6][5];
    for (int a = 0; a < 6; ++a) {
        dvec3 axis(axes[a]); int f = 0;
        for (int k = 0; k < 6; ++k) {
            dvec3 nrm(axes[k]);
            if (dot(nrm, axis) < -0.5) continue;
            Face& F = faces[a][dot(nrm, axis) > 0.5 ? 0 : ++f];
            dvec3 fc = axis + 0.5 * nrm;
            F.dir = normalize(fc);
            dvec3 u = std::abs(nrm.x) > 0.5 ? dvec3(0,1,0) : dvec3(1,0,0), v = cross(nrm, u);
            F.omega = solidAngle(dvec3(0), {fc - 0.5*u - 0.5*v, fc + 0.5*u - 0.5*v, fc + 0.5*u + 0.5*v, fc - 0.5*u + 0.5*v});
            lobe(std::getenv("CENTRAL") ? F.dir : nrm, F.lobe);
        }
    }
    auto idx = [&](int x, int y, int z) { return ((size_t(y) * P + size_t((z + P) % P)) * P + size_t((x + P) % P)) * NB; };
    std::vector<double> in(size_t(P) * P * H * NB, 0.0), out(in.size()), acc;
    double up[9]; lobe(dvec3(0, 1, 0), up);
    for (int z = 0; z < P; ++z) for (int x = 0; x < P; ++x) for (int i = 0; i < NB; ++i) in[idx(x, 0, z) + i] = up[i];
    acc = in;
    for (int step = 1; step <= maxSteps; ++step) {
        std::fill(out.begin(), out.end(), 0.0);
        for (int y = 0; y < H; ++y) for (int z = 0; z < P; ++z) for (int x = 0; x < P; ++x) {
            double* d = &out[idx(x, y, z)];
            for (int a = 0; a < 6; ++a) {
                int sx = x - axes[a].x, sy = y - axes[a].y, sz = z - axes[a].z;
                if (sy < 0 || sy >= H) continue;
                const double* s = &in[idx(sx, sy, sz)];
                for (int f = 0; f < 5; ++f) {
                    double flux = faces[a][f].omega * eval(s, faces[a][f].dir);
                    for (int i = 0; i < NB; ++i) d[i] += flux * faces[a][f].lobe[i];
                }
            }
        }
        // The floor: light leaving layer 0 downward is stopped (gather from y = -1 is skipped).
        std::swap(in, out);
        for (size_t i = 0; i < acc.size(); ++i) acc[i] += in[i];
        if (step == 1 || step == 2 || step == 4 || step == 8 || step == 16 || step == 32 || step == 64 || step == 128) {
            double E = std::max(0.0, convolveCos(&acc[idx(0, 0, 0)], dvec3(0, -1, 0)));
            std::printf("bands %d steps %3d: floor self-irradiance / exitance = %.4f\n", NB == 4 ? 2 : 3, step, E / 1.0);
        }
    }
}
