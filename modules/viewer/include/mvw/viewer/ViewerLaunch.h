#pragma once
// What `mvw view` opens, decided before the window: the PACS servers and the study (a config,
// or volumes named on the command line), or nothing but the PACS window.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "mvw/pacs/Pacs.h"
#include "mvw/study/Session.h"
#include "mvw/viewer/PacsBrowser.h"

namespace mvw::viewer {

struct ViewerLaunchOptions {
  std::string study;                   // a study config (.json); empty: none
  std::string anatomical, functional;  // volumes without a config (--anatomical, --functional)
  std::string servers;                 // --servers FILE; empty: the default servers.json
};

struct ViewerLaunch {
  // The PACS servers the PACS window offers, the file they came from, and why the default file
  // could not be used (shown in the PACS window).
  std::vector<PacsServerEntry> servers;
  std::filesystem::path serversFile;
  std::string serversProblem;
  // The study, loaded and placed; null: the window opens on the PACS window alone.
  std::unique_ptr<study::Session> session;
};

// --servers FILE must be right (bad input otherwise); a bad default file is said in the PACS
// window and the viewer opens all the same. Without a study config, --anatomical (and
// --functional) make one; without either, servers to choose from are needed (InputError
// otherwise). Everything the study names is read and placed here, before the window opens:
// bad input is reported with nothing drawn.
ViewerLaunch launchViewer(const ViewerLaunchOptions& options, const pacs::Options& pacs);

}  // namespace mvw::viewer
