// The model's reports (what `candela-tool build` writes to MODEL.report/:
// eigenfires.png, psnr.png, trajectory.png, ...), shown in the window: found
// when the model opens, each PNG uploaded the first time it is shown.
#pragma once

#include <string>
#include <vector>

#include "gl/texture.h"

namespace candela::studio {

class ReportsView {
 public:
  explicit ReportsView(const std::string& model);  // a path, or builtin:NAME (none)
  const std::string& folder() const { return folder_; }
  size_t count() const { return reports_.size(); }
  const std::string& name(size_t i) const { return reports_[i].name; }
  // Inside an ImGui window: a tab per report, the image fitted to `width`.
  void draw(float width);

 private:
  struct Report {
    std::string name, path, error;
    Texture texture;
    int width = 0, height = 0;
    bool tried = false;
  };
  void load(Report& r);
  std::string folder_;
  std::vector<Report> reports_;
};

}  // namespace candela::studio
