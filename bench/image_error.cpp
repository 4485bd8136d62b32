// image_error REFERENCE IMAGE...: each image's relative RMS error against the reference,
// sqrt(sum |I - R|^2 / sum |R|^2) over the RGB channels, one line per image ("path error"). An
// image smaller than the reference (a viewer preview) is compared as the window shows it,
// stretched to the reference's size (nearest pixel). bench/viewer_first_second.sh uses it.
#include <cmath>
#include <cstdio>
#include <exception>

#include "core/image_io.h"

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: image_error REFERENCE.exr IMAGE.exr...\n");
        return 2;
    }
    try {
        const tyndall::Image ref = tyndall::readImage(argv[1]);
        for (int i = 2; i < argc; ++i) {
            const tyndall::Image img = tyndall::readImage(argv[i]);
            double err = 0, norm = 0;
            for (int y = 0; y < ref.height; ++y)
                for (int x = 0; x < ref.width; ++x) {
                    const tyndall::Rgb& r = ref.at(x, y);
                    const tyndall::Rgb& v = img.at(x * img.width / ref.width, y * img.height / ref.height);
                    for (int c = 0; c < 3; ++c) err += double(v[c] - r[c]) * (v[c] - r[c]), norm += double(r[c]) * r[c];
                }
            std::printf("%s %.5f\n", argv[i], std::sqrt(err / std::max(norm, 1e-30)));
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "image_error: %s\n", e.what());
        return 1;
    }
    return 0;
}
