#include "mvw/output/HeadlessGl.h"

#include "mvw/core/Error.h"

namespace mvw::output {

GlChoice resolveGl(const std::string& option) {
  if (!option.empty()) return {*render::parseGlRequest(option), "--gl " + option};
  const render::GlRequest request = render::glRequestFromEnvironment();
  if (request == render::GlRequest::Auto) return {};
  return {request, std::string(render::kGlEnvironmentVariable) + "=" + render::toString(request)};
}

std::unique_ptr<render::GlContext> makeHeadlessContext(const std::string& option, glm::ivec2 size) {
  const GlChoice choice = resolveGl(option);
  try {
    return render::createHeadlessContext(size, choice.request);
  } catch (const InputError&) {
    throw;
  } catch (const Error& e) {
    if (choice.request == render::GlRequest::Auto) throw;
    throw InputError(choice.origin, e.what());
  }
}

}  // namespace mvw::output
