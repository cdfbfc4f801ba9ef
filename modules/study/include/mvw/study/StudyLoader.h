#pragma once
// Reading a study's volumes into a core Study: each source with its own DICOM series choice.
// `mvw render`, `mvw view`, `mvw info`, `mvw bench` and `mvw validate` all read through here.
#include <filesystem>

#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"
#include "mvw/core/Study.h"
#include "mvw/core/Volume.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/pacs/Pacs.h"

namespace mvw::study {

// Where a source's files are: its path, or for a PACS series ("pacs", "study", "series") the
// verified cache folder, retrieved first when it is not complete there (mvw::pacs), with `pacs`:
// the cache folder, the time-outs and the calling AE title travel with the read (the command
// line's --cache, --connect-timeout and --read-timeout; the viewer's saved server), so a read
// that becomes a retrieve is configured by its caller alone. Every read below takes them.
std::filesystem::path localPath(const config::VolumeSource& source, const pacs::Options& pacs);

// What readLocal does with a read's InputError: returns when it is not a cached PACS file's,
// else moves the series into the quarantine and throws the error naming where it went.
void rethrowQuarantined(const config::VolumeSource& source, const std::filesystem::path& folder,
                        const InputError& e, const pacs::Options& pacs);

// `read(localPath(source, pacs))`. A PACS series whose file fails to read there (the error
// names a file inside its cache folder) is moved into the cache's quarantine
// (pacs::quarantineSeries) and the error names the file where it now lies: the next run
// retrieves the series again instead of failing on the same cached file forever.
template <class Read>
auto readLocal(const config::VolumeSource& source, const pacs::Options& pacs, Read&& read) {
  const std::filesystem::path path = localPath(source, pacs);
  try {
    return read(path);
  } catch (const InputError& e) {
    rethrowQuarantined(source, path, e, pacs);
    throw;
  }
}

// The volume a study names, read with `options` and the source's own series selection.
Volume readSource(const config::VolumeSource& source, io::ReadOptions options,
                  const pacs::Options& pacs);

// The study's anatomical volume. One with neither modality nor unit (NIfTI and MetaImage carry
// neither) whose lowest value lies between -3100 and -900 and which has a tenth or more of its
// voxels at air in Hounsfield units (whole numbers in -1050 .. -950, or a scanner's padding:
// -2048, -2000, -3024) is read as a CT in HU, with a note: the CT preset, isosurface and
// window then apply instead of the MR ones. (A field map, a phase or a difference image
// reaches below -900 too, but does not pile its voxels at air.) Every command that reads a
// study's anatomy reads it here.
Volume readAnatomical(const config::VolumeSource& source, io::ReadOptions options,
                      const pacs::Options& pacs);

// The study's functional volume, read, and refused when its kind is "labels" but it holds a
// value that is not a whole number (a PET given as labels). Every command that reads a
// study's functional volume reads it here.
Volume readFunctional(const config::StudyConfig& config, io::ReadOptions options,
                      const pacs::Options& pacs);

// A path names a study config when it is a .json file (every command that takes a volume or a
// study decides so here).
bool isStudyConfig(const std::filesystem::path& path);

// Both volumes of the study (the functional one when the config names it: readFunctional).
Study loadStudy(const config::StudyConfig& config, const io::ReadOptions& options,
                const pacs::Options& pacs);

}  // namespace mvw::study
