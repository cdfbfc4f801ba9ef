#include "mvw/config/ServerList.h"

#include <cstdlib>
#include <fstream>
#include <set>
#include <utility>

#include <nlohmann/json.hpp>

#include "FieldTable.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"
#include "mvw/io/AtomicFile.h"

namespace mvw::config {

namespace {

using detail::FieldTable;
using detail::Where;
using nlohmann::json;

struct ServerListFile {
  std::vector<SavedServer> servers;
};

const char* kCredentials =
    "credentials do not belong in the server list; set MVW_PACS_USER and MVW_PACS_PASSWORD, or "
    "MVW_PACS_CREDENTIALS (a file only its owner can read)";

const FieldTable<SavedServer>& serverTable() {
  static const FieldTable<SavedServer> t = [] {
    FieldTable<SavedServer> s;
    s.add(
         "name",
         "The server's name: in the viewer's PACS window, and as SERVER on the command line "
         "(`mvw pacs find NAME`, --store NAME, a study config's \"pacs\").",
         {"string", "not empty, no \"://\" or \"@\"", "required", {}},
         [](const json& v, SavedServer& out, const Where& w) {
           out.name = detail::readString(v, w);
           if (out.name.empty()) w.bad("is empty");
           if (!isServerName(out.name))
             w.bad("must not hold \"://\" or \"@\" (it would read as a URL)");
         },
         [](const SavedServer& in, json& j, const char* k) { j[k] = in.name; })
        .add(
            "url",
            "The server: http(s)://host:port/PATH (DICOMweb) or dicom://AET@host:port (DIMSE).",
            {"string", "a server URL, no credentials", "required", {}},
            [](const json& v, SavedServer& out, const Where& w) {
              out.url = detail::readString(v, w);
              try {
                pacs::parseServer(out.url);
              } catch (const InputError& e) {
                w.bad(e.problem());
              }
            },
            [](const SavedServer& in, json& j, const char* k) { j[k] = in.url; })
        .add(
            "calling_aet", "DIMSE: the AE title mvw calls the server with (the viewer's).",
            {"string", "1 to 16 characters", "", {}},
            [](const json& v, SavedServer& out, const Where& w) {
              out.callingAet = detail::readString(v, w);
              if (!pacs::isAeTitle(out.callingAet))
                w.bad("must be an AE title: 1 to 16 characters");
            },
            [](const SavedServer& in, json& j, const char* k) { j[k] = in.callingAet; });
    return s;
  }();
  return t;
}

const FieldTable<ServerListFile>& listTable() {
  static const FieldTable<ServerListFile> t = [] {
    FieldTable<ServerListFile> l;
    l.add(
        "servers", "The saved servers, each with a name of its own.",
        {"array of objects", "", "required",
         [](const std::string& path) { return serverTable().describe(path + "[]"); }},
        [](const json& v, ServerListFile& out, const Where& w) {
          if (!v.is_array()) w.bad("must be an array");
          std::set<std::string> names;
          for (std::size_t i = 0; i < v.size(); ++i) {
            const Where at{w.file, w.key + "[" + std::to_string(i) + "]"};
            if (v[i].is_object())
              for (const char* secret : {"user", "password", "credentials", "token"})
                if (v[i].contains(secret))
                  Where{w.file, at.key + "." + secret}.bad(std::string("is not accepted: ") +
                                                           kCredentials);
            SavedServer s;
            serverTable().read(v[i], s, Where{w.file, at.key + "."});
            if (!v[i].contains("name")) at.bad("has no \"name\"");
            if (!v[i].contains("url")) at.bad("has no \"url\"");
            if (!names.insert(s.name).second)
              at.bad("repeats the name '" + s.name + "': each server has a name of its own");
            out.servers.push_back(std::move(s));
          }
        },
        [](const ServerListFile& in, json& j, const char* k) {
          json servers = json::array();
          for (const SavedServer& s : in.servers) servers.push_back(serverTable().write(s));
          j[k] = servers;
        });
    return l;
  }();
  return t;
}

}  // namespace

std::filesystem::path defaultServersFile() {
  if (const char* xdg = std::getenv("XDG_CONFIG_HOME"); xdg && *xdg)
    return std::filesystem::path(xdg) / "mvw" / "servers.json";
  const char* home = std::getenv("HOME");
  return std::filesystem::path(home && *home ? home : ".") / ".config" / "mvw" / "servers.json";
}

std::vector<SavedServer> readServerList(const std::filesystem::path& file) {
  requireReadable(file);
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file, "cannot read the server list");
  json j;
  try {
    j = parseJson(in, file);
  } catch (const json::exception& e) {
    throw InputError(file, std::string("not valid JSON: ") + e.what());
  }
  if (!j.is_object())
    throw InputError(file, "is not a server list: {\"servers\": [{\"name\": ..., \"url\": ...}]}");
  ServerListFile list;
  listTable().read(j, list, Where{file, ""});
  if (!j.contains("servers")) throw InputError(file, "missing key 'servers'");
  return list.servers;
}

void writeServerList(const std::filesystem::path& file, const std::vector<SavedServer>& servers) {
  std::error_code ec;
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path(), ec);
  io::writeTextAtomically(file, listTable().write(ServerListFile{servers}).dump(2) + "\n");
}

std::vector<ConfigKeyDoc> serverListKeyDocs() { return listTable().describe(""); }

bool isServerName(const std::string& text) {
  return text.find("://") == std::string::npos && text.find('@') == std::string::npos;
}

pacs::Server resolveServer(const std::string& text, const std::filesystem::path& serversFile) {
  if (text.empty() || !isServerName(text)) return pacs::parseServer(text);
  const char* what =
      "is neither a server URL (http(s)://host:port/PATH, dicom://AET@host:port) nor the name "
      "of a saved server";
  std::error_code ec;
  if (!std::filesystem::exists(serversFile, ec))
    throw InputError(text, std::string(what) + ": no servers are saved (" + serversFile.string() +
                               " does not exist)");
  const std::vector<SavedServer> servers = readServerList(serversFile);
  std::string names;
  for (const SavedServer& s : servers) {
    if (s.name == text) return pacs::parseServer(s.url);
    names += (names.empty() ? "'" : ", '") + s.name + "'";
  }
  throw InputError(text, std::string(what) + ": " +
                             (names.empty() ? "no servers are saved in " + serversFile.string()
                                            : serversFile.string() + " saves " + names));
}

}  // namespace mvw::config
