// Built by the config_field_needs_description test: with MVW_EMPTY_DESCRIPTION a field's
// description is "", which must stop the build (FieldTable.h's Doc); without, it compiles.
#include "FieldTable.h"

namespace {

struct Probe {
  double x = 0.0;
};

}  // namespace

void configFieldDocCheck();
void configFieldDocCheck() {
  mvw::config::detail::FieldTable<Probe> table;
#ifdef MVW_EMPTY_DESCRIPTION
  table.number("x", "", &Probe::x, 0.0, 1.0);
#else
  table.number("x", "A number.", &Probe::x, 0.0, 1.0);
#endif
}
