#include "mvw/viewer/ViewerLaunch.h"

#include <system_error>
#include <utility>

#include "mvw/core/Error.h"

namespace mvw::viewer {

ViewerLaunch launchViewer(const ViewerLaunchOptions& o, const pacs::Options& pacs) {
  ViewerLaunch v;
  if (!o.servers.empty()) {
    v.serversFile = o.servers;
    v.servers = loadServers(v.serversFile);
  } else {
    v.serversFile = defaultServersFile();
    std::error_code ec;
    if (std::filesystem::exists(v.serversFile, ec)) try {
        v.servers = loadServers(v.serversFile);
      } catch (const InputError& e) {
        v.serversProblem = e.what();
      }
  }
  config::StudyConfig study;
  if (!o.study.empty()) {
    study = config::loadStudyConfig(o.study);
  } else if (o.anatomical.empty() && !v.servers.empty()) {
    // Nothing to open yet: the window opens on the PACS window.
  } else {
    if (o.anatomical.empty())
      throw InputError("mvw view", "give a study config or --anatomical, or list PACS servers in " +
                                       v.serversFile.string() + " (or --servers FILE)");
    study.anatomical.path = o.anatomical;
    if (!o.functional.empty()) {
      study.functional = config::VolumeSource{};
      study.functional->path = o.functional;
      study.functional->frame = config::defaultFrame(study.functionalKind);
    }
  }
  if (!o.study.empty() || !o.anatomical.empty()) {
    v.session = std::make_unique<study::Session>(std::move(study));
    v.session->load(pacs);
  }
  return v;
}

}  // namespace mvw::viewer
