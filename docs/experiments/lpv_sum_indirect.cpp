// Sums the indirect layers of several voxgi renders of one view into a copy of BASE, whose
// beauty keeps BASE's direct light: for the orientation-bin experiment
// (lpv_orientation_bins.patch, docs/lpv.md). Not built with voxgi; see the patch for the command.
//   sum_indirect OUT.exr BASE.exr IN1.exr IN2.exr ...
#include <cstdio>

#include "scenes/image.h"

int main(int argc, char** argv) {
    using namespace voxgi;
    if (argc < 4) {
        std::fprintf(stderr, "usage: sum_indirect OUT.exr BASE.exr IN.exr...\n");
        return 2;
    }
    Image base = readExr(argv[2]);
    ImageLayer& indirect = base.layer("indirect");
    ImageLayer& beauty = base.layer("beauty");
    std::vector<float> sum(indirect.data.size(), 0.0f);
    for (int i = 3; i < argc; ++i) {
        const Image part = readExr(argv[i]);
        const std::vector<float>& d = part.find("indirect")->data;
        for (std::size_t k = 0; k < sum.size(); ++k) sum[k] += d[k];
    }
    for (std::size_t k = 0; k < sum.size(); ++k) {
        beauty.data[k] += sum[k] - indirect.data[k];
        indirect.data[k] = sum[k];
    }
    writeExr(argv[1], base);
    return 0;
}
