#pragma once
#include <CLI/App.hpp>

#include "mvw/pacs/Pacs.h"

namespace mvw::app {

// `mvw validate SUITE.json -o REPORT_DIR [--update] [--jobs N]`: renders every case of a
// validation suite headless with `mvw render`'s code (in child processes, N at a time, each
// rendering a share of one study's cases so that the study loads once per process, not once
// per case), compares each with its reference image under the case's tolerances (max
// per-pixel delta with an allowed fraction, mean delta, PSNR, SSIM), runs the case's analytic
// checks, and writes REPORT_DIR/index.html + report.json. Exit 0 only when every case
// passes, 1 when a case fails, 2 for a bad suite (the message names the file).
//
//   { "name": "regression",
//     "study": "${MVW_GOLDEN_STUDY}",              default study config of the cases
//     "tolerance": { "max_delta": 24, "max_delta_fraction": 0.001, "mean_delta": 0.5,
//                    "psnr": 40, "ssim": 0.99 },   defaults for the cases
//     "cases": [
//       { "name": "mip-left", "view": "mip-left",  a view of the study, by name,
//         "reference": "golden/mip-left.png" },
//       { "name": "mpr", "study": "other.json",
//         "view": { "mode": "mpr", "view": "axial", "width": 161, "height": 161 },  or inline
//         "reference": "golden/mpr.png", "tolerance": { "psnr": 35 },
//         "checks": [ { "type": "mip_equals_max_projection", "axis": "z" } ] } ] }
//
// Paths may hold ${NAME} (an environment variable) and are relative to the suite's folder.
void addValidateCommand(CLI::App& app, const pacs::Options& pacs);

}  // namespace mvw::app
