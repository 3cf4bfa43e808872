#include "named_model.h"

#include <cstdint>
#include <vector>

#include "core/error.h"
#include "embedded_models.h"

namespace candela::tools {

model::FlameModel load_named_model(const std::string& name_or_path) {
  if (name_or_path.rfind("builtin:", 0) != 0) return model::FlameModel::load(name_or_path);
  std::string name = name_or_path.substr(8);
  if (name == "candle") name = "default";  // the default model is the candle's: one file
  const auto bytes = eigen_models::find(name + ".cmodel");
  if (bytes.empty())
    throw ConfigError("<built-in models>", name_or_path,
                      "no such built-in model (built in: builtin:candle, builtin:fire)");
  return model::FlameModel::from(model::ModelFile::from_static(bytes, "<built-in " + name + ">"));
}

}  // namespace candela::tools
