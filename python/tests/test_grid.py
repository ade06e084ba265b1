"""Grids to and from numpy arrays, the ESRI ASCII reader through the bindings,
and errors: the same exception types and messages as the C++ library and the CLI."""
import numpy as np
import pytest

import talus
from conftest import cli_error


def read_asc_independently(path):
    """The grid of an .asc file parsed here, rows flipped to south-first, NODATA -> NaN."""
    lines = path.read_text().split("\n")
    header = {}
    for line in lines[:6]:
        key, value = line.split()
        header[key.lower()] = float(value)
    z = np.array([[float(t) for t in line.split()] for line in lines[6:] if line.strip()])
    z[z == header["nodata_value"]] = np.nan
    return header, z[::-1]


def test_a_bundled_dem_reads_to_the_values_of_the_file(west_bijou):
    grid = talus.read_esri_ascii(str(west_bijou))
    header, z = read_asc_independently(west_bijou)
    assert grid.shape == z.shape == (82, 122)
    h = header["cellsize"]
    assert grid.cellsize == h
    assert grid.x_min == header["xllcorner"] + h / 2 and grid.y_min == header["yllcorner"] + h / 2
    assert np.array_equal(grid.to_array(), z, equal_nan=True)
    assert np.array_equal(grid.valid_mask(), ~np.isnan(z))
    # a[j, i] is node (i, j): row 0 the south.
    i, j = 7, 3
    assert grid.bilinear(*grid.node_position(i, j)) == z[j, i]


def test_arrays_round_trip_through_the_grid_and_the_asc_writer_exactly(tmp_path):
    rng = np.random.default_rng(19)
    z = rng.normal(100.0, 30.0, size=(5, 7))
    z[1, 2] = np.nan
    valid = np.ones(z.shape, dtype=bool)
    valid[4, 6] = False
    grid = talus.ElevationGrid.from_array(z, 2.5, -10.0, 20.0, valid=valid)
    assert (grid.ncols, grid.nrows, grid.void_count()) == (7, 5, 2)
    assert grid.x_max == -10.0 + 6 * 2.5 and grid.y_max == 20.0 + 4 * 2.5
    expected = z.copy()
    expected[4, 6] = np.nan
    assert np.array_equal(grid.to_array(), expected, equal_nan=True)
    assert np.array_equal(grid.to_array(nodata=-1.0), np.where(np.isnan(expected), -1.0, z))
    path = tmp_path / "round_trip.asc"
    talus.write_esri_ascii(grid, str(path))
    back = talus.read_esri_ascii(str(path))
    assert np.array_equal(back.to_array(), expected, equal_nan=True)
    assert (back.x_min, back.y_min, back.cellsize) == (grid.x_min, grid.y_min, grid.cellsize)
    filled = talus.fill_voids(back)
    assert filled.void_count() == 0 and filled.to_array()[1, 2] in z


def test_bad_arrays_are_refused():
    with pytest.raises(TypeError):
        talus.ElevationGrid.from_array(np.zeros(4), 1.0, 0.0, 0.0)
    with pytest.raises(talus.InputError, match="cell size"):
        talus.ElevationGrid.from_array(np.zeros((3, 3)), -1.0, 0.0, 0.0)
    with pytest.raises(talus.InputError, match="finite"):
        talus.ElevationGrid.from_array(np.array([[0.0, np.inf], [0.0, 0.0]]), 1.0, 0.0, 0.0)


def test_exception_classes_follow_the_cpp_hierarchy():
    assert issubclass(talus.InputError, talus.Error) and issubclass(talus.InputError, ValueError)
    assert issubclass(talus.BaselineOptionError, talus.InputError)
    for cls in (talus.InfeasibleError, talus.SolverError):
        assert issubclass(cls, talus.Error) and not issubclass(cls, ValueError)
    assert issubclass(talus.Error, RuntimeError)


MALFORMED = "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n4 five 6\n"


def test_a_malformed_asc_raises_the_readers_message_naming_file_and_line(tmp_path, cli, rover):
    path = tmp_path / "malformed.asc"
    path.write_text(MALFORMED)
    with pytest.raises(talus.InputError) as raised:
        talus.read_esri_ascii(str(path))
    message = str(raised.value)
    assert message == f"{path}:7: value 'five' is not a number"  # file:line
    # The CLI prints the same message on stderr.
    code, _, err = cli("terrain", "info", path)
    assert code == 1
    assert cli_error(err) == message
    code, _, err = cli("plan", "--terrain", path, "--vehicle", rover, "--start", "0,0",
                       "--goal", "1,1", "--out", tmp_path / "out")
    assert code == 1 and cli_error(err) == message


def test_a_bad_vehicle_file_raises_the_readers_message(tmp_path, cli, west_bijou):
    path = tmp_path / "vehicle.yaml"
    path.write_text("model: point_mass\nfriction: slippery\ncg_height: 0.5\nhalf_track: 0.6\n")
    with pytest.raises(talus.InputError) as raised:
        talus.load_vehicle(str(path))
    assert str(path) in str(raised.value) and "friction" in str(raised.value)
    code, _, err = cli("plan", "--terrain", west_bijou, "--vehicle", path, "--start", "0,0",
                       "--goal", "1,1", "--out", tmp_path / "out")
    assert code == 1 and cli_error(err) == str(raised.value)


def test_the_fractal_generator_is_the_clis_bit_for_bit(cli, tmp_path):
    grid = talus.generate_fractal_terrain(ncols=41, nrows=31, cellsize=0.25, height_scale=1.0,
                                          undulation_amplitude=0.5, peaks=3, peak_height=0.4,
                                          seed=7)
    assert (grid.ncols, grid.nrows, grid.cellsize) == (41, 31, 0.25)
    path = tmp_path / "fractal.asc"
    code, _, err = cli("terrain", "generate", "fractal", "--ncols", 41, "--nrows", 31,
                       "--cellsize", 0.25, "--height-scale", 1.0, "--undulation-amplitude", 0.5,
                       "--peaks", 3, "--peak-height", 0.4, "--seed", 7, "-o", path)
    assert code == 0, err
    assert np.array_equal(talus.read_esri_ascii(str(path)).to_array(), grid.to_array())
    other = talus.generate_fractal_terrain(ncols=41, nrows=31, cellsize=0.25, seed=8)
    assert not np.array_equal(other.to_array(), grid.to_array())
    with pytest.raises(talus.InputError):
        talus.generate_fractal_terrain(fractal_dimension=3.5)
