// The point-mass model of Shiller & Gwo (1991): sliding, contact and lateral
// tip-over |f_q| <= (b/h) R (the shared conditions come from VehiclePhysics).
#include "../vehicle_models.hpp"

namespace talus::detail {
namespace {

class PointMassPhysics final : public VehiclePhysics {
 public:
  std::string_view name() const override { return "point_mass"; }

 protected:
  void add_model_conditions(const Vehicle& v, ForceConditions& out) const override {
    out.add_lateral_ratio(Constraint::kTipover, v.half_track / v.cg_height);
  }
};

}  // namespace

const VehiclePhysics& point_mass_physics() {
  static const PointMassPhysics physics;
  return physics;
}

}  // namespace talus::detail
