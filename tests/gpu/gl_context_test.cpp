// Headless contexts: EGL (llvmpipe here) and OSMesa through dlopen both give a 4.5 core context
// whose function table is complete; the context refuses use from another thread.
#include "gpu/gl_context.h"

#include <gtest/gtest.h>

#include <thread>

#include "core/error.h"

using namespace tyndall;

TEST(GlContext, EglGivesOpenGl45Core) {
    auto ctx = GlContext::create(GlBackend::Egl);
    ASSERT_TRUE(ctx);
    GLint major = 0, minor = 0, profile = 0;
    ctx->gl().GetIntegerv(GL_MAJOR_VERSION, &major);
    ctx->gl().GetIntegerv(GL_MINOR_VERSION, &minor);
    ctx->gl().GetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    EXPECT_GE(major * 10 + minor, 45) << ctx->description();
    EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT) << ctx->description();
    EXPECT_EQ(ctx->description().rfind("EGL", 0), 0u) << ctx->description();
    std::printf("EGL: %s (software: %d)\n", ctx->description().c_str(), int(ctx->isSoftware()));
}

TEST(GlContext, OSMesaLoadedAtRunTimeGivesOpenGl45Core) {
    auto ctx = GlContext::create(GlBackend::OSMesa);
    ASSERT_TRUE(ctx);
    GLint major = 0, minor = 0;
    ctx->gl().GetIntegerv(GL_MAJOR_VERSION, &major);
    ctx->gl().GetIntegerv(GL_MINOR_VERSION, &minor);
    EXPECT_GE(major * 10 + minor, 45) << ctx->description();
    EXPECT_EQ(ctx->description().rfind("OSMesa", 0), 0u) << ctx->description();
    EXPECT_TRUE(ctx->isSoftware());
}

TEST(GlContext, ContextsComeAndGoInOneProcess) {
    for (int i = 0; i < 3; ++i) {
        auto a = GlContext::create(GlBackend::Egl);
        ASSERT_TRUE(a);
        a.reset();
        auto b = GlContext::create(GlBackend::OSMesa);
        ASSERT_TRUE(b);
    }
}

TEST(GlContext, RefusesUseFromAnotherThread) {
    auto ctx = GlContext::create();
    EXPECT_NO_THROW(ctx->requireCurrentThread());
    bool threw = false;
    std::thread([&] {
        try {
            ctx->requireCurrentThread();
        } catch (const Error&) {
            threw = true;
        }
    }).join();
    EXPECT_TRUE(threw);
}
