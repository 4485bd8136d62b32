#pragma once
// A rectangle of film pixels: the render region (RenderSettings::region; `tyndall render --region
// X Y W H`, a scene's or view file's render block "region": [X, Y, W, H], the viewer's region
// drag). Only its pixels are traced and splatted; a pass leaves every other pixel 0. Pixels are
// counted from the image's top-left corner, rows downward, as in the output image.
namespace tyndall {

struct PixelRegion {
    int x = 0, y = 0;
    int width = 0, height = 0;  ///< 0 x 0 = no region: the whole image

    bool whole() const { return width == 0 && height == 0; }
    /// The pixels rendered in a w x h image: this region, or the whole image when there is none.
    PixelRegion in(int w, int h) const { return whole() ? PixelRegion{0, 0, w, h} : *this; }
    bool contains(int px, int py) const { return px >= x && py >= y && px < x + width && py < y + height; }
    /// Inside a w x h image, at least one pixel, or the whole image (no region).
    bool fits(int w, int h) const {
        return whole() || (x >= 0 && y >= 0 && width >= 1 && height >= 1 && x + width <= w && y + height <= h);
    }
    bool operator==(const PixelRegion& o) const {
        return x == o.x && y == o.y && width == o.width && height == o.height;
    }
    bool operator!=(const PixelRegion& o) const { return !(*this == o); }
};

}  // namespace tyndall
