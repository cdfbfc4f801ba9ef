#pragma once
// The PACS servers saved by name (servers.json): read and written through a field table, so
// the file appears in the config reference and a bad one is refused with a message naming the
// file and the key. resolveServer turns every SERVER argument (`mvw pacs`, --store, a study
// config's "pacs") into a server: a URL as it is, anything else a name saved here.
#include <filesystem>
#include <string>
#include <vector>

#include "mvw/config/ConfigReference.h"
#include "mvw/pacs/Pacs.h"

namespace mvw::config {

// One saved server: its name (in the viewer's PACS window and as a SERVER argument), its URL
// as `mvw pacs` takes it, and the AE title mvw calls a DIMSE server with. Never credentials
// (MVW_PACS_USER / MVW_PACS_PASSWORD or MVW_PACS_CREDENTIALS).
struct SavedServer {
  std::string name;
  std::string url;
  std::string callingAet = "MVW";
};

// $XDG_CONFIG_HOME/mvw/servers.json, or ~/.config/mvw/servers.json: the viewer's and the
// CLI's.
std::filesystem::path defaultServersFile();

// {"servers": [{"name": ..., "url": ..., "calling_aet": ...}, ...]}, strictly: an unknown key,
// a URL that is not a SERVER (pacs::parseServer), an empty or repeated name, a name that reads
// as a URL, a calling AE title that is not one, and credentials are InputErrors naming the file.
std::vector<SavedServer> readServerList(const std::filesystem::path& file);

// The list as readServerList reads it back (atomically; the folder is made).
void writeServerList(const std::filesystem::path& file, const std::vector<SavedServer>& servers);

// Every key of servers.json, for the reference.
std::vector<ConfigKeyDoc> serverListKeyDocs();

// True when SERVER is a name rather than a URL: it has neither "://" nor '@'.
bool isServerName(const std::string& text);

// SERVER as the user gave it: a URL (http(s)://..., dicom://AET@host:port) is parsed as it is;
// anything else is a name looked up in `serversFile`. An unknown name is an InputError listing
// the names saved (or saying none are, and where the file would be).
pacs::Server resolveServer(const std::string& text,
                           const std::filesystem::path& serversFile = defaultServersFile());

}  // namespace mvw::config
