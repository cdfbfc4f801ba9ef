#include "mvw/batch/BatchRun.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <ostream>
#include <sstream>
#include <vector>

#include "mvw/batch/BatchFolders.h"
#include "mvw/batch/BatchHashCache.h"
#include "mvw/batch/BatchInputs.h"
#include "mvw/batch/BatchProcess.h"
#include "mvw/batch/BatchRecord.h"
#include "mvw/batch/BatchReport.h"
#include "mvw/batch/BatchResume.h"
#include "mvw/core/Error.h"
#include "mvw/core/ExitCode.h"
#include "mvw/io/AtomicFile.h"
#include "mvw/io/Interrupt.h"
#include "mvw/process/ProcessPool.h"
#include "mvw/process/Sha256.h"

namespace mvw::batch {

namespace fs = std::filesystem;

namespace {

// The inputs a failed.json records for a study that could not be started: every checksum
// when they can be had, else the study config's alone ("" when even it cannot be read), so
// that the record always says what the study was run on.
std::map<std::string, std::string> inputsAsFarAsReadable(const BatchStudy& study) {
  try {
    return batchInputChecksums(study);
  } catch (const std::exception&) {
  }
  try {
    return {{study.study.string(), process::fileSha256(study.study)}};
  } catch (const std::exception&) {
    return {{study.study.string(), ""}};
  }
}

}  // namespace

BatchRunCounts runBatch(const BatchManifest& manifest, const BatchRunOptions& options,
                        std::ostream& progress) {
  const fs::path out = fs::absolute(options.out).lexically_normal();
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec || !fs::is_directory(out))
    throw InputError(options.out, "cannot be made as the output folder: " + ec.message());
  if (::access(out.c_str(), W_OK) != 0) throw InputError(options.out, "is not writable");
  std::vector<std::string> ids;
  for (const auto& s : manifest.studies) ids.push_back(s.id);
  writeBatchIndex(out, manifest.file, ids);

  // The pool forks its launcher now, before anything starts threads.
  process::ProcessPool pool(mvwJobFunction(options.mvwExecutable));

  BatchRunCounts counts;
  const RecordContext context{manifest.file, options.version};
  std::vector<StudyRun> pending;
  // Ctrl-C or scancel's SIGTERM removes the work folders of the studies not yet published
  // (io::installInterruptCleanup): OUT keeps only complete studies.
  std::vector<io::RemovedOnInterrupt> pendingGuards;
  std::vector<process::ProcessJob> jobs;
  const std::vector<const BatchStudy*> mine = shardStudies(manifest, options.shard);
  counts.total = static_cast<int>(mine.size());

  auto line = [&](const std::string& id, const std::string& what) {
    const int left = counts.total - counts.done - counts.skipped - counts.failed;
    progress << "[" << (counts.done + counts.skipped) << " done, " << counts.failed << " failed, "
             << left << " left] " << id << ": " << what << std::endl;
  };
  auto recordFailure = [&](const StudyRun& run, int status, const std::string& message,
                           double seconds) {
    discardFailedOutput(*run.study, run.work);
    writeRecord(run.work / "failed.json", failedRecord(run, context, status, message, seconds));
    publish(run.work, out, run.study->id);
    ++counts.failed;
    line(run.study->id, "failed (exit " + std::to_string(status) + "): " + message);
  };

  // OUT is listed once here, not once per study: the cost per study stays flat at any size.
  const Leftovers leftovers = findLeftovers(out);
  const int count = options.shard.count;
  BatchHashCache hashes(out / "hashes",
                        count == 1 ? std::string("all.tsv")
                                   : "shard-" + std::to_string(options.shard.index) + "-of-" +
                                         std::to_string(count) + ".tsv",
                        options.verify);
  for (const BatchStudy* study : mine) {
    removeLeftovers(leftovers, study->id);
    StudyRun run{study, workFolder(out, study->id), {}, {}};
    // A study whose inputs cannot be read fails as its process would: the same code and message,
    // in its log.txt too (the report links it), with the command and the inputs it would have
    // run on in failed.json.
    std::ostringstream problem;
    const int status = runReportingErrors(
        [&] {
          run.inputs = batchInputChecksums(*study, &hashes);
          run.command = batchCommand(*study, run.work, options.mvwOptions);
          return kExitSuccess;
        },
        problem);
    if (status != kExitSuccess) {
      std::string message = problem.str();
      fs::create_directories(run.work);
      const io::RemovedOnInterrupt workGuard(run.work);
      io::writeTextAtomically(run.work / "log.txt", message);
      if (!message.empty() && message.back() == '\n') message.pop_back();
      if (run.command.empty())
        run.command = batchCommandOrPlain(*study, run.work, options.mvwOptions);
      if (run.inputs.empty()) run.inputs = inputsAsFarAsReadable(*study);
      recordFailure(run, status, message, 0.0);
      continue;
    }
    if (decideStudy(out / study->id, *study, run.inputs) == StudyAction::kSkip) {
      ++counts.skipped;
      line(study->id, "done before, skipped");
      continue;
    }
    fs::create_directories(run.work);
    pendingGuards.emplace_back(run.work);
    jobs.push_back(batchJob(*study, run.work, run.command));
    pending.push_back(std::move(run));
  }
  hashes.save();

  pool.run(jobs, std::max(1, options.jobs), options.timeoutS,
           [&](std::size_t k, const process::ProcessResult& result) {
             const StudyRun& run = pending[k];
             if (result.status != 0) {
               recordFailure(run, result.status,
                             batchFailureMessage(result, run.work / "log.txt", options.timeoutS),
                             result.seconds);
               pendingGuards[k].release();
               return;
             }
             // done.json is the last file written: it exists only beside complete outputs.
             writeRecord(run.work / "done.json", doneRecord(run, context, result.seconds));
             publish(run.work, out, run.study->id);
             pendingGuards[k].release();
             ++counts.done;
             char secs[32];
             std::snprintf(secs, sizeof secs, "%.1f", result.seconds);
             line(run.study->id, std::string("done (") + secs + " s)");
           });
  progress << "batch: " << counts.done << " done now, " << counts.skipped << " done before, "
           << counts.failed << " failed, of " << counts.total << " in shard " << options.shard.index
           << "/" << options.shard.count << std::endl;
  return counts;
}

}  // namespace mvw::batch
