"""Vehicles from dicts, YAML text and files: one reader, one set of rules."""
import math

import pytest

import talus

ROVER = {"model": "point_mass", "gravity": 9.81, "friction": 0.7, "cg_height": 0.5,
         "half_track": 0.6, "max_speed": 15, "max_accel": 3, "max_decel": 6}
FIELDS = ("model", "gravity", "friction", "cg_height", "half_track", "half_wheelbase",
          "max_speed", "max_accel", "max_decel")


def same(a, b):
    return all(getattr(a, f) == getattr(b, f) for f in FIELDS)


def test_a_dict_gives_the_vehicle_of_the_file(rover):
    from_file = talus.load_vehicle(str(rover))
    from_dict = talus.Vehicle.from_dict(ROVER)
    assert same(from_file, from_dict)
    assert from_dict.model == talus.VehicleModel.POINT_MASS and from_dict.max_accel == 3.0


def test_to_dict_round_trips_and_omits_unlimited_limits(data_dir):
    rigid = talus.load_vehicle(str(data_dir / "vehicles" / "rover_rigid.yaml"))
    assert same(talus.Vehicle.from_dict(rigid.to_dict()), rigid)
    d = talus.Vehicle.from_dict({"model": "point_mass", "friction": 0.1 + 0.2,
                                 "cg_height": 0.5, "half_track": 0.6}).to_dict()
    assert d["friction"] == 0.1 + 0.2  # numbers pass through their exact repr
    assert "max_speed" not in d and "half_wheelbase" not in d
    assert talus.Vehicle.from_dict({**d, "max_speed": math.inf}).max_speed == math.inf


def test_to_dict_keeps_the_body_of_a_simulated_vehicle(data_dir):
    ugv_file = data_dir / "vehicles" / "iagnemma_ugv.yaml"
    d = talus.load_vehicle(str(ugv_file)).to_dict()
    assert d["mass"] == 2.0 and d["suspension_stiffness"] == 316.0
    assert d["inertia_roll"] == 0.01265 and d["cornering_stiffness"] == 8.0
    # The round trip through the file reader gives the same dict, body included.
    assert talus.Vehicle.from_dict(d).to_dict() == d
    # A vehicle without a body has none of its keys.
    assert "mass" not in talus.Vehicle.from_dict(ROVER).to_dict()


@pytest.mark.parametrize("change, words", [
    ({"foo": 1}, "unknown key 'foo'"),
    ({"friction": "slippery"}, "key 'friction' must be a number"),
    ({"friction": -1.0}, "friction"),
    ({"model": "hovercraft"}, "key 'model' must be point_mass or rigid_body"),
    ({"model": "rigid_body"}, "missing required key 'half_wheelbase'"),
])
def test_bad_dicts_raise_the_file_readers_messages(change, words):
    with pytest.raises(talus.InputError) as raised:
        talus.Vehicle.from_dict({**ROVER, **change}, source="my rover")
    assert words in str(raised.value)
    text = "".join(f"{k}: {v}\n" for k, v in {**ROVER, **change}.items())
    with pytest.raises(talus.InputError) as from_text:
        talus.parse_vehicle(text, "my rover")
    assert str(from_text.value) == str(raised.value)


def test_a_missing_key_and_a_wrong_value_type():
    with pytest.raises(talus.InputError, match="dict: missing required key 'friction'"):
        talus.Vehicle.from_dict({"model": "point_mass", "cg_height": 0.5, "half_track": 0.6})
    with pytest.raises(TypeError):
        talus.Vehicle.from_dict({**ROVER, "friction": [0.7]})


def test_fields_are_writable_and_validate_names_the_field():
    v = talus.Vehicle()
    v.friction = -0.5
    with pytest.raises(talus.InputError, match="friction"):
        v.validate()


def test_axle_friction_round_trips_and_needs_a_rigid_body(data_dir):
    """axle_friction judges friction at the lighter axle (only a rigid body has axles); the
    dict keeps it when set and omits it otherwise."""
    ugv = talus.load_vehicle(str(data_dir / "vehicles" / "iagnemma_ugv.yaml"))
    d = ugv.to_dict()
    assert "axle_friction" not in d
    d["axle_friction"] = True
    axle = talus.Vehicle.from_dict(d)
    assert axle.axle_friction
    assert axle.to_dict()["axle_friction"] is True
    point = {"model": "point_mass", "friction": 0.7, "cg_height": 0.5, "half_track": 0.6,
             "axle_friction": True}
    with pytest.raises(talus.InputError, match="axle_friction"):
        talus.Vehicle.from_dict(point)
