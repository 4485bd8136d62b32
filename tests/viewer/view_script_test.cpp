// The --script format: parsing and its errors.
#include <gtest/gtest.h>

#include "core/error.h"
#include "viewer/view_script.h"

namespace tyndall {
namespace {

TEST(ViewScript, ParsesEveryCommandAndExpandsDrags) {
    auto e = parseViewScript(
        "# comment\n"
        "wait-passes 4 30\n"
        "drag left 10 20 30 20 4 ctrl+shift  # orbit\n"
        "press right 5 6\nmove 7 8\nrelease right 7 8\n"
        "double-click 1 2\nscroll 3 4 -2\nkey F\nkey 3\nexposure 2.5\nsave out/a\nscreenshot s.png\n"
        "sleep 100\nwait-frames 3\nwait-input 2 9\nquit\n",
        "t.txt");
    ASSERT_EQ(e.size(), 1u + 6u + 3u + 11u);
    EXPECT_EQ(e[e.size() - 2].op, ScriptOp::WaitInput);
    EXPECT_EQ(e[e.size() - 2].value, 2);
    EXPECT_EQ(e[e.size() - 2].timeout, 9);
    EXPECT_EQ(e[0].op, ScriptOp::WaitPasses);
    EXPECT_EQ(e[0].value, 4);
    EXPECT_EQ(e[0].timeout, 30);
    EXPECT_EQ(e[1].op, ScriptOp::Press);
    EXPECT_EQ(e[1].modifiers, kModCtrl | kModShift);
    EXPECT_EQ(e[2].op, ScriptOp::Move);
    EXPECT_FLOAT_EQ(e[2].x, 15.0f);
    EXPECT_EQ(e[5].op, ScriptOp::Move);
    EXPECT_FLOAT_EQ(e[5].x, 30.0f);
    EXPECT_EQ(e[6].op, ScriptOp::Release);
    EXPECT_EQ(e[7].button, 1);
    EXPECT_EQ(e[11].op, ScriptOp::Scroll);
    EXPECT_EQ(e[11].value, -2);
    EXPECT_EQ(e[13].text, "3");
    EXPECT_EQ(e[15].text, "out/a");
    EXPECT_EQ(e.back().op, ScriptOp::Quit);
}

TEST(ViewScript, ParsesEmission) {
    auto e = parseViewScript("emission 2 0.25\n", "t.txt");
    ASSERT_EQ(e.size(), 1u);
    EXPECT_EQ(e[0].op, ScriptOp::Emission);
    EXPECT_EQ(e[0].medium, 2);
    EXPECT_EQ(e[0].value, 0.25);
    EXPECT_THROW(parseViewScript("emission 0 -1\n", "t.txt"), Error);
    EXPECT_THROW(parseViewScript("emission 0\n", "t.txt"), Error);
}

TEST(ViewScript, ParsesTransparentOnAndOff) {
    auto e = parseViewScript("transparent on\ntransparent off\n", "t.txt");
    ASSERT_EQ(e.size(), 2u);
    EXPECT_EQ(e[0].op, ScriptOp::Transparent);
    EXPECT_EQ(e[0].value, 1);
    EXPECT_EQ(e[1].op, ScriptOp::Transparent);
    EXPECT_EQ(e[1].value, 0);
    for (const char* bad : {"transparent\n", "transparent yes\n", "transparent on off\n"}) {
        try {
            parseViewScript(bad, "t.txt");
            ADD_FAILURE() << "accepted: " << bad;
        } catch (const Error& err) {
            EXPECT_NE(std::string(err.what()).find("t.txt: line 1: transparent"), std::string::npos) << err.what();
        }
    }
}

TEST(ViewScript, ParsesWaitReloadAndTheF5Key) {
    auto e = parseViewScript("wait-reload 2 30\nkey F5\nwait-reload 3\n", "t.txt");
    ASSERT_EQ(e.size(), 3u);
    EXPECT_EQ(e[0].op, ScriptOp::WaitReload);
    EXPECT_EQ(e[0].value, 2);
    EXPECT_EQ(e[0].timeout, 30);
    EXPECT_EQ(e[1].op, ScriptOp::Key);
    EXPECT_EQ(e[1].text, "F5");
    EXPECT_EQ(e[2].timeout, 600);
}

TEST(ViewScript, ErrorsNameTheFileLineAndWhatWasExpected) {
    auto message = [](const std::string& text) {
        try {
            parseViewScript(text, "s.txt");
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_EQ(message("quit\nfly 1 2\n").rfind("s.txt: line 2: unknown command 'fly'", 0), 0u) << message("fly");
    EXPECT_NE(message("press up 1 2").find("expected left, right or middle"), std::string::npos);
    EXPECT_NE(message("key Q").find("key: expected F, R"), std::string::npos);
    EXPECT_NE(message("wait-passes 0").find("passes must be a number"), std::string::npos);
    EXPECT_NE(message("move 1").find("missing y"), std::string::npos);
    EXPECT_NE(message("quit now").find("unexpected 'now'"), std::string::npos);
    EXPECT_NE(message("press left 1 2 meta").find("modifiers are"), std::string::npos);
}

}  // namespace
}  // namespace tyndall
