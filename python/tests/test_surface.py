"""Surface evaluation on arrays: the interpolating fit reproduces a plane and a
bicubic, broadcasting, and agreement with the path frames the limits use."""
import math

import numpy as np
import pytest

import talus


def grid_of(f, ncols=12, nrows=9, h=0.5, x0=1.0, y0=-2.0):
    x = x0 + h * np.arange(ncols)
    y = y0 + h * np.arange(nrows)
    X, Y = np.meshgrid(x, y)  # shape (nrows, ncols): row 0 the south
    return talus.ElevationGrid.from_array(f(X, Y), h, x0, y0)


def test_a_plane_is_reproduced_with_its_gradient_normal_and_zero_hessian():
    a, b, c = 0.3, -0.2, 5.0
    surface = talus.BPatch.interpolate(grid_of(lambda x, y: a * x + b * y + c))
    x = np.linspace(surface.x_min, surface.x_max, 7)
    y = np.linspace(surface.y_min, surface.y_max, 5)[:, None]
    z = surface.height(x, y)
    assert z.shape == (5, 7)
    assert np.allclose(z, a * x + b * y + c, rtol=0, atol=1e-12)
    grad = surface.gradient(x, y)
    assert grad.shape == (5, 7, 2)
    assert np.allclose(grad, [a, b], rtol=0, atol=1e-12)
    n = surface.normal(x, y)
    assert n.shape == (5, 7, 3)
    assert np.allclose(n, np.array([-a, -b, 1.0]) / math.sqrt(1 + a * a + b * b), atol=1e-12)
    assert np.allclose(surface.hessian(x, y), 0.0, atol=1e-12)
    assert surface.height(2.0, 0.0).shape == ()  # numbers in, a 0-d array out


def test_a_bicubic_is_reproduced_with_its_derivatives():
    def f(x, y):
        return 0.01 * x**3 - 0.02 * x * y**2 + 0.1 * x * y + y

    surface = talus.BPatch.interpolate(grid_of(f))
    x, y = np.array([1.3, 3.7, 5.9]), np.array([-1.9, 0.4, 1.8])
    assert np.allclose(surface.height(x, y), f(x, y), atol=1e-12)
    expected = np.stack([0.03 * x**2 - 0.02 * y**2 + 0.1 * y, -0.04 * x * y + 0.1 * x + 1], -1)
    assert np.allclose(surface.gradient(x, y), expected, atol=1e-12)
    hess = surface.hessian(x, y)
    assert np.allclose(hess[:, 0, 0], 0.06 * x, atol=1e-11)
    assert np.allclose(hess[:, 0, 1], -0.04 * y + 0.1, atol=1e-11)
    assert np.allclose(hess[:, 1, 1], -0.04 * x, atol=1e-11)
    assert surface.degree == 3


def test_the_biquintic_fit_reproduces_a_quintic_and_other_degrees_are_input_errors():
    def f(x, y):
        return 1e-4 * x**5 - 2e-3 * x**2 * y**3 + 0.1 * x * y + y

    surface = talus.BPatch.interpolate(grid_of(f), degree=5)
    assert surface.degree == 5
    x, y = np.array([1.3, 3.7, 5.9]), np.array([-1.9, 0.4, 1.8])
    assert np.allclose(surface.height(x, y), f(x, y), atol=1e-11)
    with pytest.raises(talus.InputError):
        talus.BPatch.interpolate(grid_of(f), degree=4)


def test_a_point_outside_the_domain_is_an_input_error():
    surface = talus.BPatch.interpolate(grid_of(lambda x, y: 0 * x))
    with pytest.raises(talus.InputError, match="outside"):
        surface.height(np.array([1.5, 100.0]), 0.0)
    assert not surface.contains(100.0, 0.0) and surface.on_data(2.0, 0.0)


def test_the_path_frames_sit_on_the_surface_and_share_its_normal(west_bijou, rover):
    surface = talus.BPatch.interpolate(talus.read_esri_ascii(str(west_bijou)))
    curve = talus.Curve2.interpolate(np.array([[557000.0, 4373500.0], [557400.0, 4373900.0],
                                               [557800.0, 4374200.0]]))
    path = talus.SurfacePath(surface, curve)
    limits = talus.VelocityLimits(talus.load_vehicle(str(rover)), path, 200)
    p = limits.points
    # The same patch evaluated at the same points: bit for bit.
    assert np.array_equal(p[:, 2], surface.height(p[:, 0], p[:, 1]))
    # k_r is the vertical component of the surface normal r.
    assert np.array_equal(limits.k_r, surface.normal(p[:, 0], p[:, 1])[:, 2])
    assert np.array_equal(curve.evaluate(np.array([0.0, 1.0])), [[557000.0, 4373500.0],
                                                                  [557800.0, 4374200.0]])
