#pragma once
#include <CLI/App.hpp>

#include "mvw/pacs/Pacs.h"

namespace mvw::app {

// `mvw convert INPUT -o OUT.nii.gz|.nii|.mha`: the volume every other command reads, written
// as NIfTI or MetaImage, with a JSON sidecar (OUT.json) saying what it is, as dcm2niix does.
void addConvertCommand(CLI::App& app, const pacs::Options& pacs);

}  // namespace mvw::app
