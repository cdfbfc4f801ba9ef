#pragma once
// A batch study's folders in OUT: it works in OUT/.work-<id>-<pid>/ and is published as
// OUT/<id>/ when its command has ended, the last result stepping aside as OUT/.old-<id>-<pid>/
// for the moment of the rename. A killed run leaves only such dot folders, which the next run of
// that study deletes before it starts.
#include <filesystem>
#include <string>
#include <unordered_map>
#include <vector>

namespace mvw::batch {

// OUT/.work-<id>-<pid> for this process.
std::filesystem::path workFolder(const std::filesystem::path& out, const std::string& id);

// What killed runs left in OUT, by study id: OUT/.work-<id>-* and OUT/.old-<id>-* (the part
// after the id holding no '-', so study "a" never takes study "a-b"'s folders). A run lists OUT
// once with findLeftovers, not once per study: a cohort's rerun beside 100,000 folders would
// otherwise cost studies x folders.
using Leftovers = std::unordered_map<std::string, std::vector<std::filesystem::path>>;
Leftovers findLeftovers(const std::filesystem::path& out);

// Deletes the leftovers of this study. Shards are disjoint, so no other live task works on this
// id.
void removeLeftovers(const Leftovers& leftovers, const std::string& id);

// The same for one study, listing OUT.
void removeLeftovers(const std::filesystem::path& out, const std::string& id);

// Moves the finished work folder into OUT/<id>. The old result steps aside first, so no moment
// has a done.json in OUT/<id> that is not this run's or the last complete run's.
void publish(const std::filesystem::path& work, const std::filesystem::path& out,
             const std::string& id);

}  // namespace mvw::batch
