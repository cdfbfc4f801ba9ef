#include "BatchCommand.h"

#include "CommandBody.h"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "mvw/batch/BatchManifest.h"
#include "mvw/batch/BatchProcess.h"
#include "mvw/batch/BatchReport.h"
#include "mvw/batch/BatchRun.h"
#include "mvw/batch/BatchShard.h"
#include "mvw/batch/BatchSlurm.h"
#include "mvw/core/ExitCode.h"
#include "mvw/core/Format.h"
#include "mvw/core/Version.h"

namespace mvw::app {

namespace {

namespace fs = std::filesystem;

struct BatchOptions {
  std::string manifest, out, shard, partition, time, mem;
  int shards = 0, jobs = 1, tasks = 0, throttle = 0;
  double timeoutS = 3600.0;
  bool submit = false, verify = false;
};

// mvw's own options given to the batch command that its studies need too: the PACS cache (made
// absolute: a Slurm task starts elsewhere) and the time-outs where they are not the defaults.
std::vector<std::string> mvwOptionsOf(const pacs::Options& pacs) {
  std::vector<std::string> o;
  if (!pacs.cacheDir.empty())
    o.insert(o.end(), {"--cache", fs::absolute(pacs.cacheDir).lexically_normal().string()});
  const pacs::Options defaults;
  if (pacs.connectTimeoutS != defaults.connectTimeoutS)
    o.insert(o.end(), {"--connect-timeout", shortNumber(pacs.connectTimeoutS)});
  if (pacs.readTimeoutS != defaults.readTimeoutS)
    o.insert(o.end(), {"--read-timeout", shortNumber(pacs.readTimeoutS)});
  return o;
}

// What each task's command takes, read from its own command line (their one definition): a
// manifest option none of them takes is refused when the manifest is loaded, naming its line,
// not by every study's command once the cohort runs. Long names only: the child gets `--NAME`.
batch::TaskOptions taskOptionsOf(const CLI::App& app) {
  batch::TaskOptions known;
  for (const std::string& task : batch::batchTasks()) {
    auto& options = known[task];
    const CLI::App* command = app.get_subcommand(task);
    // Its own options, and mvw's (--cache and the time-outs), which every command takes.
    std::vector<const CLI::Option*> all = command->get_options();
    for (const CLI::Option* o : app.get_options())
      if (o != app.get_help_ptr() && !o->check_lname("version")) all.push_back(o);
    for (const CLI::Option* o : all) {
      if (o->get_positional() || o == command->get_help_ptr()) continue;
      batch::TaskOption how;
      how.flag = o->get_expected_max() == 0 || o->get_type_size_max() == 0;
      how.maxValues = std::max(1, o->get_items_expected_max());
      for (const std::string& name : o->get_lnames()) options[name] = how;
    }
  }
  return known;
}

}  // namespace

void addBatchCommand(CLI::App& app, const pacs::Options& pacs) {
  auto opt = std::make_shared<BatchOptions>();
  CLI::App* cohort = app.add_subcommand(
      "batch",
      "Cohorts: a manifest of studies run one by one (resumable), sharded for Slurm "
      "or Kubernetes, and its report");
  cohort->require_subcommand(1);

  CLI::App* run = cohort->add_subcommand(
      "run",
      "Run the studies of a manifest (or of one shard of it) into OUT/<id>/, skipping "
      "those already done");
  run->add_option("manifest", opt->manifest, "Cohort manifest (.csv: id,study,task,... or .json)")
      ->required();
  run->add_option("-o,--output", opt->out, "Output folder")->required();
  run->add_option("--shard", opt->shard,
                  "I/N: run shard I of N (default: SLURM_ARRAY_TASK_ID/SLURM_ARRAY_TASK_COUNT)");
  run->add_option("--shards", opt->shards,
                  "N shards, this one JOB_COMPLETION_INDEX (a Kubernetes Indexed Job)")
      ->check(CLI::Range(1, 100000));
  run->add_option("--jobs,-j", opt->jobs, "Studies at once")->check(CLI::Range(1, 256));
  run->add_option("--timeout", opt->timeoutS, "Seconds a study may take before it is killed")
      ->check(CLI::Range(1.0, 7 * 24 * 3600.0));
  run->add_flag("--verify", opt->verify,
                "Hash every input again (default: an input whose size, modification time and "
                "inode are unchanged keeps the SHA-256 remembered in OUT/hashes/)");
  setCommandBody(*run, [opt, &pacs, &app] {
    const batch::BatchShard shard = batch::resolveBatchShard(opt->shard, opt->shards);
    const batch::BatchManifest manifest =
        batch::loadBatchManifest(opt->manifest, taskOptionsOf(app));
    batch::BatchRunOptions o;
    o.out = opt->out;
    o.shard = shard;
    o.jobs = opt->jobs;
    o.timeoutS = opt->timeoutS;
    o.mvwExecutable = batch::selfExecutable();
    o.mvwOptions = mvwOptionsOf(pacs);
    o.version = kVersion;
    o.verify = opt->verify;
    const batch::BatchRunCounts counts = batch::runBatch(manifest, o, std::cout);
    // A failed study is neither bad input to this command nor an internal fault: exit 1, the
    // studies said why (mvw batch report lists them).
    return counts.failed ? kExitFailure : kExitSuccess;
  });

  CLI::App* report = cohort->add_subcommand(
      "report",
      "Merge OUT's results into OUT/summary.csv, OUT/stats.csv and OUT/index.html; "
      "exit 0 only when every study is done");
  report->add_option("output", opt->out, "Output folder of mvw batch run")->required();
  setCommandBody(*report, [opt] {
    const batch::BatchReportCounts c = batch::writeBatchReport(opt->out);
    std::cout << "batch report: " << c.done << " done, " << c.failed << " failed, " << c.notRun
              << " not run; " << (fs::path(opt->out) / "index.html").string() << "\n";
    return c.failed || c.notRun ? kExitFailure : kExitSuccess;
  });

  CLI::App* slurm = cohort->add_subcommand(
      "slurm",
      "Write OUT/batch.sbatch, a Slurm array job of N tasks each running one shard; "
      "--submit submits it");
  slurm->add_option("manifest", opt->manifest, "Cohort manifest")->required();
  slurm->add_option("-o,--output", opt->out, "Output folder")->required();
  slurm->add_option("--tasks", opt->tasks, "Array tasks (shards)")
      ->required()
      ->check(CLI::Range(1, 100000));
  slurm->add_option("--jobs,-j", opt->jobs, "Studies at once in each task (its CPUs)")
      ->check(CLI::Range(1, 256));
  slurm->add_option("--partition", opt->partition, "Slurm partition");
  slurm->add_option("--time", opt->time, "Time limit of each task (e.g. 01:00:00)");
  slurm->add_option("--mem", opt->mem, "Memory of each task (e.g. 8G)");
  slurm->add_option("--throttle", opt->throttle, "At most K tasks at once (the array's %K)")
      ->check(CLI::Range(1, 100000));
  slurm->add_flag("--submit", opt->submit, "Submit with sbatch and print the job id");
  slurm->callback([opt, &pacs, &app] {
    // The manifest is checked now, not by N failing tasks later.
    batch::loadBatchManifest(opt->manifest, taskOptionsOf(app));
    batch::SlurmJobOptions o;
    o.manifest = opt->manifest;
    o.out = opt->out;
    o.mvwExecutable = batch::selfExecutable();
    o.tasks = opt->tasks;
    o.jobs = opt->jobs;
    o.throttle = opt->throttle;
    o.partition = opt->partition;
    o.time = opt->time;
    o.mem = opt->mem;
    o.mvwOptions = mvwOptionsOf(pacs);
    // The controller's limit is checked before anything is written or submitted: a larger array
    // is the user's request to change, not the server's failure.
    if (opt->submit) batch::checkSlurmArraySize(opt->tasks, batch::slurmMaxArraySize());
    const fs::path script = batch::writeSlurmScript(o);
    if (!opt->submit) {
      std::cout << script.string() << "\n";
      return;
    }
    const std::string id = batch::submitSlurmScript(script);
    std::cout << "Submitted array job " << id << " (" << opt->tasks
              << " tasks): " << script.string() << "\n";
  });
}

}  // namespace mvw::app
