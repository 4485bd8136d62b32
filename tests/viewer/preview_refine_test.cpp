// Restart on change, refine on release: the viewer's state machine, without threads or a window.
#include <gtest/gtest.h>

#include "viewer/preview_refine.h"
#include "viewer/render_loop.h"

namespace tyndall {
namespace {

TEST(PreviewRefine, AtRestItRefinesAndAChangeRestartsTheRefinementAtOnce) {
    PreviewRefine s;
    PreviewRefine::Job job = s.nextJob();
    EXPECT_EQ(job.mode, RenderMode::Refine);
    EXPECT_FALSE(s.stale(job));
    EXPECT_TRUE(s.changed());  // a key or a slider click: interrupt the refinement now
    EXPECT_TRUE(s.stale(job));
    PreviewRefine::Job next = s.nextJob();
    EXPECT_EQ(next.mode, RenderMode::Refine);
    EXPECT_GT(next.version, job.version);
    EXPECT_FALSE(s.stale(next));
}

TEST(PreviewRefine, ADragPreviewsWithoutInterruptingPreviewsAndRefinesOnRelease) {
    PreviewRefine s;
    PreviewRefine::Job refine = s.nextJob();
    EXPECT_FALSE(s.began());  // pressing alone changes nothing
    EXPECT_FALSE(s.stale(refine));
    EXPECT_TRUE(s.changed());  // the first motion stops the refinement
    PreviewRefine::Job preview = s.nextJob();
    EXPECT_EQ(preview.mode, RenderMode::Preview);
    // Further motion: the preview pass under way finishes (not interrupted) but is then stale,
    // so the next preview shows the newest view.
    EXPECT_FALSE(s.changed());
    EXPECT_TRUE(s.stale(preview));
    PreviewRefine::Job preview2 = s.nextJob();
    EXPECT_EQ(preview2.mode, RenderMode::Preview);
    EXPECT_FALSE(s.stale(preview2));  // held still: previews keep accumulating
    // Release: the preview stops now and a refinement of the released view starts from pass 0.
    EXPECT_TRUE(s.ended());
    EXPECT_TRUE(s.stale(preview2));
    PreviewRefine::Job final = s.nextJob();
    EXPECT_EQ(final.mode, RenderMode::Refine);
    EXPECT_GT(final.version, preview2.version);
    EXPECT_FALSE(s.stale(final));
}

TEST(PreviewRefine, AClickWithoutMotionKeepsTheRefinement) {
    PreviewRefine s;
    PreviewRefine::Job job = s.nextJob();
    EXPECT_FALSE(s.began());
    EXPECT_FALSE(s.ended());
    EXPECT_FALSE(s.stale(job));
    EXPECT_EQ(s.wantedMode(), RenderMode::Refine);
}

TEST(PreviewSettings, ReduceResolutionAndPhotonsOnly) {
    RenderSettings full;
    full.width = 512, full.height = 384, full.photonsPerPass = 4000, full.alpha = 0.7;
    RenderSettings p = previewSettings(full, PreviewOptions{2, 4});
    EXPECT_EQ(p.width, 256);
    EXPECT_EQ(p.height, 192);
    EXPECT_EQ(p.photonsPerPass, 1000u);
    EXPECT_EQ(p.alpha, 0.7);
    EXPECT_EQ(p.seed, full.seed);
    // A render region is in full-resolution pixels: the preview shows the whole view.
    full.region = {300, 200, 100, 50};
    EXPECT_TRUE(previewSettings(full, PreviewOptions{2, 4}).region.whole());
    EXPECT_NO_THROW(previewSettings(full, PreviewOptions{2, 4}).validate());
    RenderSettings tiny = previewSettings(RenderSettings{}, PreviewOptions{10000, 100000});
    EXPECT_GE(tiny.width, 1);
    EXPECT_GE(tiny.photonsPerPass, 1u);
}

}  // namespace
}  // namespace tyndall
