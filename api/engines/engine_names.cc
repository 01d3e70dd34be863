#include "api/engines/engine_names.h"

#include <cctype>
#include <stdexcept>

#include "core/engines/engine_registry.h"
#include "core/engines/product_pipeline.h"

namespace orbit {

std::string SessionEngineName(v1::Engine engine) {
  if (engine == v1::ENGINE_UNSPECIFIED || !v1::Engine_IsValid(engine)) return "";
  std::string name = v1::Engine_Name(engine).substr(std::string_view("ENGINE_").size());
  for (char& c : name) {
    c = c == '_' ? '-' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return name;
}

std::vector<std::string> SessionEngineNames() {
  std::vector<std::string> names;
  for (int value = v1::Engine_MIN; value <= v1::Engine_MAX; ++value) {
    if (!v1::Engine_IsValid(value)) continue;
    std::string name = SessionEngineName(static_cast<v1::Engine>(value));
    if (!name.empty()) names.push_back(std::move(name));
  }
  return names;
}

v1::Engine ParseSessionEngine(std::string_view name) {
  for (int value = v1::Engine_MIN; value <= v1::Engine_MAX; ++value) {
    if (v1::Engine_IsValid(value) && !name.empty() &&
        SessionEngineName(static_cast<v1::Engine>(value)) == name) {
      return static_cast<v1::Engine>(value);
    }
  }
  std::string known;
  for (const std::string& n : SessionEngineNames()) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown engine \"" + std::string(name) + "\" (engines: " + known +
                              ")");
}

v1::Engine ProductSessionEngine() { return ParseSessionEngine(Product().engine); }

bool RunsHmm(v1::Engine engine) {
  const std::string name = SessionEngineName(engine);
  for (const EngineKind& kind : EngineKinds()) {
    if (kind.name == name) return kind.keeps_hmm;
  }
  return false;
}

}  // namespace orbit
