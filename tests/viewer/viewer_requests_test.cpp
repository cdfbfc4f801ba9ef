// What the state and the script ask of the window loop: each request is taken once, and the
// status line and the scripted drag's flag hold until they are set again.
#include "mvw/viewer/ViewerRequests.h"

#include <gtest/gtest.h>

#include "mvw/viewer/ViewerState.h"

namespace mvw::viewer {
namespace {

TEST(ViewerRequests, ScreenshotRequestsAreTakenOnce) {
  ViewerRequests requests;
  EXPECT_EQ(requests.takeScreenshotRequest(), std::nullopt);
  EXPECT_EQ(requests.takePaneScreenshotRequest(), std::nullopt);
  requests.requestScreenshot("a.png");
  requests.requestScreenshot("b.png");  // the later request wins
  requests.requestPaneScreenshot(kCoronal, "coronal.png");
  EXPECT_EQ(requests.takeScreenshotRequest(), std::filesystem::path("b.png"));
  EXPECT_EQ(requests.takeScreenshotRequest(), std::nullopt);
  const auto pane = requests.takePaneScreenshotRequest();
  ASSERT_TRUE(pane.has_value());
  EXPECT_EQ(pane->first, kCoronal);
  EXPECT_EQ(pane->second, std::filesystem::path("coronal.png"));
  EXPECT_EQ(requests.takePaneScreenshotRequest(), std::nullopt);
}

TEST(ViewerRequests, QuitStatusAndScriptedInteractionHold) {
  ViewerRequests requests;
  EXPECT_FALSE(requests.quitRequested());
  EXPECT_TRUE(requests.status().empty());
  EXPECT_FALSE(requests.scriptedInteraction());
  requests.requestQuit();
  requests.setStatus("saved a.png");
  requests.setScriptedInteraction(true);
  EXPECT_TRUE(requests.quitRequested());
  EXPECT_TRUE(requests.quitRequested());
  EXPECT_EQ(requests.status(), "saved a.png");
  EXPECT_TRUE(requests.scriptedInteraction());
  requests.setScriptedInteraction(false);
  EXPECT_FALSE(requests.scriptedInteraction());
}

}  // namespace
}  // namespace mvw::viewer
