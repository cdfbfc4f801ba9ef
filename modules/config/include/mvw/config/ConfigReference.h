#pragma once
// The study config's reference (docs/config-reference.md, `mvw config reference`), made from
// the field tables that parse the config: every key the parser accepts, with its type, the
// values it takes, its default and its one-line description.
#include <string>
#include <vector>

namespace mvw::config {

// One key of a study config as its field table describes it.
struct ConfigKeyDoc {
  std::string object;  // the key path of the object it sits in: "" (the top), "render.views[]"
  std::string key;     // its own key path: "name", "render.views[].zoom" ([] : any element)
  std::string type;    // "number", "integer", "boolean", "string", "object", "array of ..."
  std::string values;  // what it takes: "0.001 .. 1000", "linear or nearest" ("": any)
  // Its default: JSON (defaultIsJson) where an absent key means a value, else what an absent
  // key means in words ("unset", "required", "off").
  std::string defaultValue;
  bool defaultIsJson = false;
  std::string description;  // one line
};

// Every key of a study config, from the field tables: each object's keys in table order, the
// keys of an object-valued key right after it.
std::vector<ConfigKeyDoc> studyConfigKeyDocs();

// The reference as Markdown, headed by a line saying that it is generated and by what.
std::string studyConfigReference();

}  // namespace mvw::config
