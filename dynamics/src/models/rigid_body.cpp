// The rigid body on four wheels of Mann & Shiller (2006), geometric stability
// criterion: the resultant of gravity and inertia passes through the support
// rectangle (±l, ±b), i.e. lateral tip-over |f_q| <= (b/h) R and longitudinal
// tip-over (pitch) |f_t| <= (l/h) R; R is the chassis' total normal load and
// contact is judged at each wheel (wheel_contact.hpp). See dynamics/DERIVATION.md.
#include "../vehicle_models.hpp"

namespace talus::detail {
namespace {

class RigidBodyPhysics final : public VehiclePhysics {
 public:
  std::string_view name() const override { return "rigid_body"; }
  bool contact_at_wheels() const override { return true; }
  double axle_load_transfer(const Vehicle& v) const override {
    return v.axle_friction ? v.cg_height / v.half_wheelbase : 0.0;
  }

 protected:
  void add_model_conditions(const Vehicle& v, ForceConditions& out) const override {
    out.add_lateral_ratio(Constraint::kTipover, v.half_track / v.cg_height);
    out.add_tangential_ratio(Constraint::kPitchover, v.half_wheelbase / v.cg_height);
  }
};

}  // namespace

const VehiclePhysics& rigid_body_physics() {
  static const RigidBodyPhysics physics;
  return physics;
}

}  // namespace talus::detail
