#pragma once
// Labels burnt into images (the halves of `tyndall compare`): a built-in 5x7 bitmap font, so it
// works headless with no font files. Covers A-Z (lower case is drawn as upper case), 0-9, space
// and . , : ; - + = / ( ) % ' _ #; other characters draw as a hollow box.
#include <string>

#include "core/image.h"

namespace tyndall::app {

/// Width and height in image pixels of `text` drawn at `scale` (font pixels are scale x scale),
/// including a one-font-pixel margin all round.
int labelWidth(const std::string& text, int scale);
int labelHeight(int scale);

/// Draws `text` with the margin box's top-left at pixel (x, y): the box filled with `backdrop`,
/// the glyphs in `color`. Clipped to the image.
void drawLabel(Image& image, int x, int y, const std::string& text, int scale, const Rgb& color, const Rgb& backdrop);

}  // namespace tyndall::app
