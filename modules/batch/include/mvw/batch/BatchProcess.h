#pragma once
// The run of one batch study as a child mvw process (`mvw render|stats|register`): its command
// line, the job function the process pool runs (exec of the mvw executable, stdout to a file
// for stats), and the message a failed run leaves for the report. A crash or hang is that
// study's failure, not the run's.
#include <filesystem>
#include <string>
#include <vector>

#include "mvw/batch/BatchManifest.h"
#include "mvw/process/ProcessPool.h"

namespace mvw::batch {

// The command line (after the executable) that runs `study` with its outputs in `folder`, then
// `mvwOptions` (mvw's own options the batch run was given: --cache and the PACS time-outs, so
// that a study naming PACS series reads the cache the run was told of). A register study whose
// config names a PACS series registers the config itself (`register STUDY.json`); one of local
// files names them (--fixed, --moving). Throws InputError when a register study's config has no
// functional volume.
std::vector<std::string> batchCommand(const BatchStudy& study, const std::filesystem::path& folder,
                                      const std::vector<std::string>& mvwOptions = {});

// The same command when the study cannot be run (its config is not valid): what the user would
// run to see the problem, for failed.json. Never throws.
std::vector<std::string> batchCommandOrPlain(const BatchStudy& study,
                                             const std::filesystem::path& folder,
                                             const std::vector<std::string>& mvwOptions = {});

// The pool job of a study: args[0] is where its stdout goes ("" = the job's log, for render and
// register; stats.json in its work folder for stats), the rest is `command`.
process::ProcessJob batchJob(const BatchStudy& study, const std::filesystem::path& work,
                             const std::vector<std::string>& command);

// What the pool's children run for batchJob's arguments: `exe` exec'd with them (exit 127 and a
// message when it cannot be started).
process::JobFunction mvwJobFunction(const std::filesystem::path& exe);

// Removes what a failed run wrote that is no result: the stdout file of a stats run (stats.json,
// empty or cut short). The log and the markers stay.
void discardFailedOutput(const BatchStudy& study, const std::filesystem::path& work);

// The message of a failed run for failed.json and the report: the last line the command said
// ("mvw: error: ..." when there is one), after why it was killed when it was.
std::string batchFailureMessage(const process::ProcessResult& result,
                                const std::filesystem::path& log, double timeoutS);

// This very binary (/proc/self/exe), which the children and the Slurm tasks run. Throws
// mvw::Error when it cannot be found.
std::filesystem::path selfExecutable();

}  // namespace mvw::batch
