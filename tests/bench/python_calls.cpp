// Issue 54's benchmark (not a test): the C++ calls the Python module `mvw` makes, timed in a
// C++ loop, for tests/bench/python-overhead to set against the same calls from Python. Each
// line printed is one call: "OP WALL_S CPU_S" (CPU: the process's, every thread's).
//
//   mvw_python_calls_bench read PATH N             study::readConversionInput (mvw.read)
//   mvw_python_calls_bench stats PATH X Y Z R N    study::roiReport + roiReportJson (mvw.stats
//                                                  with sphere=(X, Y, Z, R)) of PATH read once
//   mvw_python_calls_bench render CONFIG N         each view of CONFIG N times through the
//                                                  command's painter (mvw.Study(CONFIG).render)
//
// The first call of each op is a warm-up and is not printed (Python's first calls load NumPy).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mvw/config/StudyConfig.h"
#include "mvw/output/HeadlessGl.h"
#include "mvw/output/StudyRender.h"
#include "mvw/pacs/Pacs.h"
#include "mvw/render/VolumeRenderer.h"
#include "mvw/study/RoiReport.h"
#include "mvw/study/Session.h"
#include "mvw/study/VolumeConversion.h"

namespace {

double processCpuS() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Runs `call` n + 1 times, printing each call but the first.
void timed(const std::string& op, int n, const std::function<void()>& call) {
  for (int i = 0; i <= n; ++i) {
    const auto wall = std::chrono::steady_clock::now();
    const double cpu = processCpuS();
    call();
    const double cpuS = processCpuS() - cpu;
    const double wallS =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count();
    if (i > 0) std::printf("%s %.9f %.9f\n", op.c_str(), wallS, cpuS);
  }
}

mvw::Volume read(const std::string& path) {
  mvw::study::ConversionRequest request;
  request.input = path;
  return mvw::study::readConversionInput(request, mvw::pacs::Options{});
}

}  // namespace

int main(int argc, char** argv) {
  using namespace mvw;
  const std::vector<std::string> args(argv + 1, argv + argc);
  try {
    if (args.size() == 3 && args[0] == "read") {
      timed("read", std::atoi(args[2].c_str()), [&] { read(args[1]); });
    } else if (args.size() == 7 && args[0] == "stats") {
      const Volume volume = read(args[1]);
      study::RoiOptions roi;
      for (int i = 2; i < 6; ++i) roi.sphere.push_back(std::atof(args[i].c_str()));
      timed("stats", std::atoi(args[6].c_str()), [&] {
        const study::RoiReport report =
            study::roiReport(volume, study::roiRequestOf(roi), args[1], [](const std::string&) {});
        static_cast<void>(study::roiReportJson(report).dump());
      });
    } else if (args.size() == 3 && args[0] == "render") {
      // As mvw.Study's constructor (and output::renderStudy) sets a study up.
      study::Session session(config::loadStudyConfig(args[1]));
      auto context = output::makeHeadlessContext("");
      session.load(pacs::Options{});
      render::VolumeRenderer renderer(*context, session.anatomical(),
                                      render::parseGradientSource("auto"));
      session.attach(renderer);
      const std::vector<study::PlannedView> planned = session.views(renderer);
      for (const study::PlannedView& v : planned)
        timed("render:" + v.config.name, std::atoi(args[2].c_str()), [&] {
          static_cast<void>(output::viewPainter(renderer, session, v)(v.settings).image);
        });
    } else {
      std::fprintf(stderr,
                   "usage: mvw_python_calls_bench read PATH N | stats PATH X Y Z R N | "
                   "render CONFIG N\n");
      return 2;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mvw_python_calls_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
