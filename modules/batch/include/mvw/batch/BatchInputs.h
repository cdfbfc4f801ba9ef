#pragma once
// What a batch study's run depends on, as checksums: done.json records them, and a later run
// skips the study only while they are unchanged (BatchResume).
#include <map>
#include <string>

#include "mvw/batch/BatchHashCache.h"
#include "mvw/batch/BatchManifest.h"

namespace mvw::batch {

// SHA-256 of the study config and of every local file it and the options name (a folder: every
// file in it, in name order: process::pathSha256), keyed by absolute path. A series on a PACS
// is keyed by pacsInputKey and its checksum is that key's: it counts as unchanged while the
// config names the same server, study and series (mvw does not ask the server at every run; a
// series changed on the server reruns after its done study's folder is deleted). Throws InputError
// naming a file that cannot be read ("an input of a batch study") or a study config that is
// not valid. With a cache, a file whose stat is unchanged keeps its remembered hash.
std::map<std::string, std::string> batchInputChecksums(const BatchStudy& study,
                                                       BatchHashCache* cache = nullptr);

// "pacs SERVER study UID series SERIES", the server as the config names it (a study config
// refuses a URL holding credentials: they never reach done.json).
std::string pacsInputKey(const std::string& server, const std::string& study,
                         const std::string& series);

}  // namespace mvw::batch
