#pragma once
// What is known about `mvw render`'s output folder before anything renders. The views wait in
// an io::StagedFolder until every one of them is written (StudyRender.cpp).
#include <filesystem>

namespace mvw::output {

// Everything about the output folder that can be known before rendering is said then, so a
// name the file system cannot take costs no render and creates nothing: the nearest folder
// that exists must be a writable folder, and each folder still to be made a name it can hold.
// Throws InputError naming outDir.
void checkOutputFolder(const std::filesystem::path& outDir);

}  // namespace mvw::output
