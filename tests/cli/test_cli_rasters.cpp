// `talus` with GDAL rasters: --terrain GeoTIFF everywhere, terrain info's CRS,
// --reproject, terrain traversability's GeoTIFF and preview, plan --rasters.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "cli_test_support.hpp"
#include "gdal_test_support.hpp"

namespace talus::cli_test {
namespace {

namespace fs = std::filesystem;

const std::string kWestBijouAsc = data_file("terrain/west_bijou_escarpment_nasadem25m.asc");

/// The West Bijou DEM as a GeoTIFF in UTM 13N, written by GDAL.
std::string west_bijou_tif() {
  const std::string tif = scratch_file("west_bijou.tif");
  if (!fs::exists(tif)) {
    gdal_test::translate(kWestBijouAsc, tif, {"-of", "GTiff", "-a_srs", "EPSG:32613"});
  }
  return tif;
}

/// A 0.01° DEM in EPSG:4326 near West Bijou, a gentle slope east.
std::string geographic_tif() {
  const std::string tif = scratch_file("geographic.tif");
  const int nx = 41, ny = 31;
  const double dx = 0.01 / 40.0;
  std::vector<double> values;
  for (int r = 0; r < ny; ++r) {
    for (int c = 0; c < nx; ++c) values.push_back(1700.0 + 0.5 * c + 0.2 * r);
  }
  gdal_test::write_raster(tif, nx, ny, {-104.305, dx, 0.0, 39.505, 0.0, -dx}, "EPSG:4326", values);
  return tif;
}

TEST(CliRasters, TerrainInfoOfAGeoTiffEqualsTheAscsAndAddsTheCrs) {
  const RunResult asc = run_talus("terrain info " + quoted(kWestBijouAsc));
  const RunResult tif = run_talus("terrain info " + quoted(west_bijou_tif()));
  ASSERT_EQ(asc.exit_code, 0) << asc.err;
  ASSERT_EQ(tif.exit_code, 0) << tif.err;
  const nlohmann::json a = parse_json(asc.out, "asc info"), t = parse_json(tif.out, "tif info");
  for (const char* key : {"ncols", "nrows", "cellsize", "xmin", "xmax", "zmin", "zmax", "voids"}) {
    EXPECT_EQ(a.at(key), t.at(key)) << key;
  }
  EXPECT_NEAR(a.at("ymin").get<double>(), t.at("ymin").get<double>(), 1e-8);
  EXPECT_TRUE(a.at("crs").is_null());
  EXPECT_EQ(a.at("driver"), "esri-ascii");
  EXPECT_EQ(t.at("driver"), "GTiff");
  EXPECT_EQ(t.at("crs").at("epsg"), 32613);
  EXPECT_NE(t.at("crs").at("label").get<std::string>().find("UTM zone 13N"), std::string::npos);
  EXPECT_EQ(t.at("reprojected"), false);
}

// Issue #39 item 3: a multi-band file was read silently as band 1. Now the DEM must have one
// band or the command names it with --band (declared once for every terrain option).
TEST(CliRasters, AMultiBandDemNeedsItsBandNamed) {
  const std::string tif = scratch_file("two_bands.tif");
  gdal_test::translate(kWestBijouAsc, tif,
                       {"-of", "GTiff", "-a_srs", "EPSG:32613", "-b", "1", "-b", "1"});
  const RunResult plain = run_talus("terrain info " + quoted(tif));
  EXPECT_EQ(plain.exit_code, 1);
  EXPECT_NE(plain.err.find("the raster has 2 bands"), std::string::npos) << plain.err;
  const RunResult second = run_talus("terrain info " + quoted(tif) + " --band 2");
  const RunResult asc = run_talus("terrain info " + quoted(kWestBijouAsc));
  ASSERT_EQ(second.exit_code, 0) << second.err;
  const nlohmann::json a = parse_json(asc.out, "asc info"), b = parse_json(second.out, "band 2");
  for (const char* key : {"ncols", "nrows", "zmin", "zmax", "voids"})
    EXPECT_EQ(a.at(key), b.at(key));
  const RunResult third = run_talus("terrain info " + quoted(tif) + " --band 3");
  EXPECT_EQ(third.exit_code, 1);
  EXPECT_NE(third.err.find("band 3 requested, the raster has 2"), std::string::npos) << third.err;
  // The same option on a command that plans: it reaches load_terrain.
  const RunResult plan = run_talus("plan --terrain " + quoted(tif) + " --vehicle " +
                                   quoted(data_file("vehicles/rover.yaml")) +
                                   " --start 557100,4373600 --goal 557300,4373700 --stage global"
                                   " --no-figures --out " +
                                   quoted(scratch_file("two_bands_plan")));
  EXPECT_EQ(plan.exit_code, 1);
  EXPECT_NE(plan.err.find("2 bands"), std::string::npos) << plan.err;
}

TEST(CliRasters, GeographicDemIsRefusedWithoutReprojectAndPlansAfterIt) {
  const std::string tif = geographic_tif();
  const RunResult refused = run_talus("terrain info " + quoted(tif));
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_EQ(count_lines(refused.err), 1u) << refused.err;
  EXPECT_NE(refused.err.find("geographic (degrees)"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("--reproject auto"), std::string::npos) << refused.err;

  const RunResult info = run_talus("terrain info --reproject auto " + quoted(tif));
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const nlohmann::json j = parse_json(info.out, "info");
  EXPECT_EQ(j.at("crs").at("epsg"), 32613);
  EXPECT_EQ(j.at("source_crs").at("epsg"), 4326);
  EXPECT_EQ(j.at("reprojected"), true);
  const double x0 = j.at("xmin").get<double>(), x1 = j.at("xmax").get<double>();
  const double y0 = j.at("ymin").get<double>(), y1 = j.at("ymax").get<double>();
  const auto at = [](double a, double b, double t) { return std::to_string(a + t * (b - a)); };
  const std::string vehicle = point_mass_vehicle("geo_rover.yaml", 0.7, 10.0);
  const std::string plan_args = "--terrain " + quoted(tif) + " --vehicle " + quoted(vehicle) +
                                " --start " + at(x0, x1, 0.3) + "," + at(y0, y1, 0.5) + " --goal " +
                                at(x0, x1, 0.7) + "," + at(y0, y1, 0.5) +
                                " --stage global --candidates 1";
  const std::string dir = scratch_file("geo_plan");
  fs::remove_all(dir);
  const RunResult no = run_talus("plan " + plan_args + " --out " + quoted(dir));
  EXPECT_EQ(no.exit_code, 1);
  EXPECT_NE(no.err.find("--reproject auto"), std::string::npos) << no.err;
  EXPECT_FALSE(fs::exists(dir + "/summary.json"));
  const RunResult yes =
      run_talus("plan " + plan_args + " --reproject auto --rasters --out " + quoted(dir));
  ASSERT_EQ(yes.exit_code, 0) << yes.err;
  const nlohmann::json plan = parse_json(yes.out, "plan");
  EXPECT_EQ(plan.at("status"), "ok");
  EXPECT_NE(plan.at("crs").get<std::string>().find("EPSG:32613"), std::string::npos);
}

TEST(CliRasters, TraversabilityOfAPlaneIsTheSideSlopeClosedForm) {
  // tan(slope) = 1 rising east: a point mass with mu 0.7 < b/h = 1.2 slides across it.
  const std::string plane = generate_terrain(
      "trav_plane.asc",
      "plane --slope 0.7853981633974483 --aspect 0 --ncols 12 --nrows 10 --cellsize 2");
  const std::string vehicle = point_mass_vehicle("trav_rover.yaml", 0.7, 8.0);
  const std::string out = scratch_file("trav.tif");
  const RunResult r =
      run_talus("terrain traversability --terrain " + quoted(plane) + " --vehicle " +
                quoted(vehicle) + " --headings 8 -o " + quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = parse_json(r.out, "traversability");
  EXPECT_EQ(j.at("bands").size(), 11u);
  EXPECT_TRUE(fs::exists(scratch_file("trav.png")));
  const gdal_test::ReadRaster raster = gdal_test::read_raster(out);
  ASSERT_EQ(raster.nx, 12);
  ASSERT_EQ(raster.ny, 10);
  EXPECT_EQ(raster.gt[1], 2.0);
  ASSERT_EQ(raster.bands.size(), 11u);
  EXPECT_EQ(raster.bands[0].description, "speed_limit_heading_000");
  EXPECT_EQ(raster.bands[7].description, "speed_limit_heading_007");
  EXPECT_EQ(raster.bands[8].description, "speed_limit_min");
  EXPECT_EQ(raster.bands[9].description, "binding_constraint");
  EXPECT_EQ(raster.bands[10].description, "untraversable");
  for (const auto& band : raster.bands) {
    ASSERT_TRUE(band.nodata);
    EXPECT_EQ(*band.nodata, -9999.0);
  }
  // Heading k at 45 k degrees, phi = heading - aspect: stable iff 0.7 D >= |sin phi| with
  // D = sqrt(1 + cos^2 phi) (tan alpha = 1): east/west (k = 0, 4) pass, 45° too (0.857 >=
  // 0.707), north/south (k = 2, 6: 0.7 < 1) do not.
  const double expected[8] = {8, 8, 0, 8, 8, 8, 0, 8};
  for (std::size_t k = 0; k < 8; ++k) {
    for (const double v : raster.bands[k].values) ASSERT_EQ(v, expected[k]) << "heading " << k;
  }
  for (const double v : raster.bands[8].values) EXPECT_EQ(v, 0.0);
  for (const double v : raster.bands[9].values) EXPECT_EQ(v, 1.0);  // sliding
  for (const double v : raster.bands[10].values) EXPECT_EQ(v, 0.0);
}

TEST(CliRasters, TraversabilityKeepsTheDemsCrsAndNodata) {
  // West Bijou with a hole: the hole is NODATA in every band, the CRS is the DEM's.
  const std::string tif = scratch_file("holey.tif");
  {
    gdal_test::ReadRaster dem = gdal_test::read_raster(west_bijou_tif());
    std::vector<double> values = dem.bands[0].values;
    values[10 * dem.nx + 20] = -9999.0;
    gdal_test::write_raster(tif, dem.nx, dem.ny, dem.gt, "EPSG:32613", values, -9999.0);
  }
  const std::string vehicle = point_mass_vehicle("trav_rover2.yaml", 0.7, 8.0);
  const std::string out = scratch_file("holey_trav.tif");
  const RunResult r = run_talus("terrain traversability --terrain " + quoted(tif) + " --vehicle " +
                                quoted(vehicle) + " --headings 4 -o " + quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = parse_json(r.out, "traversability");
  EXPECT_EQ(j.at("nodata_nodes"), 1);
  const gdal_test::ReadRaster raster = gdal_test::read_raster(out);
  EXPECT_EQ(gdal_test::epsg_of_wkt(raster.wkt), 32613);
  const gdal_test::ReadRaster dem = gdal_test::read_raster(tif);
  for (int k = 0; k < 6; ++k) EXPECT_EQ(raster.gt[k], dem.gt[k]) << k;
  for (const auto& band : raster.bands) {
    EXPECT_EQ(band.values[10 * raster.nx + 20], -9999.0) << band.description;
    EXPECT_NE(band.values[10 * raster.nx + 21], -9999.0) << band.description;
  }
}

TEST(CliRasters, BadInputsGiveOneLineAndWriteNothing) {
  const std::string vehicle = point_mass_vehicle("bad_rover.yaml", 0.7, 8.0);
  const std::string rotated = scratch_file("rotated.tif");
  gdal_test::write_raster(rotated, 4, 4, {0.0, 1.0, 0.1, 10.0, 0.1, -1.0}, "EPSG:32613",
                          std::vector<double>(16, 1.0));
  const std::string out = scratch_file("never.tif");
  expect_bad_input(
      "terrain traversability",
      {{"--terrain " + quoted(scratch_file("missing.tif")) + " --vehicle " + quoted(vehicle) +
            " -o " + quoted(out),
        "missing.tif: no such file"},
       {"--terrain " + quoted(rotated) + " --vehicle " + quoted(vehicle) + " -o " + quoted(out),
        "the raster is rotated"},
       {"--terrain " + quoted(geographic_tif()) + " --vehicle " + quoted(vehicle) + " -o " +
            quoted(out),
        "--reproject auto"},
       {"--terrain " + quoted(kWestBijouAsc) + " --vehicle " + quoted(vehicle) +
            " --headings 0 -o " + quoted(out),
        "--headings must be between 1 and 360"},
       {"--terrain " + quoted(kWestBijouAsc) + " --vehicle " + quoted(scratch_file("nope.yaml")) +
            " -o " + quoted(out),
        "nope.yaml"},
       {"--terrain " + quoted(kWestBijouAsc) + " --vehicle " + quoted(vehicle) + " -o " +
            quoted(scratch_file("dir_missing/x.tif")),
        "x.png"}},
      out);
  EXPECT_FALSE(fs::exists(scratch_file("never.png")));
  expect_bad_input("terrain info", {{quoted(rotated), "rotated"}}, out);
}

// Issue #39 item 1: an output that is a file the terrain read reached (here the source of a
// VRT, which the --terrain check alone did not see) is refused with one line and left as it
// was; before, `terrain traversability --terrain in.vrt -o src.tif` replaced the DEM.
TEST(CliRasters, AnOutputOntoAFileTheTerrainReachedIsRefusedAndTheFileKept) {
  const fs::path dir = scratch_file("vrt_outputs");
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string src = (dir / "src.tif").string();
  gdal_test::translate(kWestBijouAsc, src,
                       {"-of", "GTiff", "-a_srs", "EPSG:32613", "-srcwin", "0", "0", "20", "20"});
  const std::string vrt = (dir / "in.vrt").string();
  write_text(vrt,
             "<VRTDataset rasterXSize=\"20\" rasterYSize=\"20\">\n"
             "  <SRS>EPSG:32613</SRS>\n"
             "  <GeoTransform>557000, 25, 0, 4373500, 0, -25</GeoTransform>\n"
             "  <VRTRasterBand dataType=\"Float32\" band=\"1\">\n    <SimpleSource>\n"
             "      <SourceFilename relativeToVRT=\"1\">src.tif</SourceFilename>\n"
             "      <SourceBand>1</SourceBand>\n    </SimpleSource>\n  </VRTRasterBand>\n"
             "</VRTDataset>\n");
  const std::string before = read_text(src);
  const std::string vehicle = point_mass_vehicle("vrt_rover.yaml", 0.7, 8.0);
  const RunResult r = run_talus("terrain traversability --terrain " + quoted(vrt) + " --vehicle " +
                                quoted(vehicle) + " -o " + quoted(src));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("is an input of this run"), std::string::npos) << r.err;
  EXPECT_EQ(read_text(src), before) << "the VRT's source was replaced";
  EXPECT_FALSE(fs::exists(dir / "src.png"));
  // Another name is written as usual.
  const RunResult ok = run_talus("terrain traversability --terrain " + quoted(vrt) + " --vehicle " +
                                 quoted(vehicle) + " -o " + quoted((dir / "out.tif").string()));
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  // A world file beside the DEM is an input too (GDAL lists it): an output of its name is
  // refused and the georeferencing kept.
  const std::string dem = (dir / "dem.tif").string(), world = (dir / "dem.tfw").string();
  gdal_test::translate(
      kWestBijouAsc, dem,
      {"-of", "GTiff", "-a_srs", "EPSG:32613", "-srcwin", "0", "0", "20", "20", "-co", "TFW=YES"});
  ASSERT_TRUE(fs::exists(world));
  const std::string world_before = read_text(world);
  const RunResult onto_world = run_talus("terrain traversability --terrain " + quoted(dem) +
                                         " --vehicle " + quoted(vehicle) + " -o " + quoted(world));
  EXPECT_EQ(onto_world.exit_code, 1) << onto_world.err;
  EXPECT_NE(onto_world.err.find("is an input of this run"), std::string::npos) << onto_world.err;
  EXPECT_EQ(read_text(world), world_before);
}

TEST(CliRasters, PlanRastersWritesCostToGoInTheDemsCrsAndRfc7946GeoJson) {
  const std::string dir = scratch_file("plan_rasters");
  fs::remove_all(dir);
  const std::string vehicle = point_mass_vehicle("plan_rover.yaml", 0.7, 10.0);
  // West Bijou spans x 556609 .. 559634, y 4373160 .. 4375185 (node domain).
  const RunResult r =
      run_talus("plan --terrain " + quoted(west_bijou_tif()) + " --vehicle " + quoted(vehicle) +
                " --start 557200,4373700 --goal 558600,4374600 --stage global "
                "--candidates 2 --lattice-spacing 50 --rasters --out " +
                quoted(dir));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = parse_json(r.out, "plan");
  const gdal_test::ReadRaster cost = gdal_test::read_raster(dir + "/cost_to_go.tif");
  ASSERT_EQ(cost.bands.size(), 3u);
  EXPECT_EQ(cost.bands[0].description, "cost_from_start");
  EXPECT_EQ(cost.bands[1].description, "cost_to_goal");
  EXPECT_EQ(cost.bands[2].description, "unreachable");
  EXPECT_EQ(cost.nx, j.at("lattice")[0].get<int>());
  EXPECT_EQ(cost.ny, j.at("lattice")[1].get<int>());
  EXPECT_EQ(cost.gt[1], j.at("lattice_spacing").get<double>());
  EXPECT_EQ(gdal_test::epsg_of_wkt(cost.wkt), 32613);
  // The start node costs 0 from the start; the goal node 0 to the goal; the two fields agree on
  // the best candidate's cost at the start (within float32 rounding).
  const auto pixel = [&](const nlohmann::json& node) {
    const int c =
        static_cast<int>(std::lround((node[0].get<double>() - cost.gt[0]) / cost.gt[1] - 0.5));
    const int row =
        static_cast<int>(std::lround((node[1].get<double>() - cost.gt[3]) / cost.gt[5] - 0.5));
    return static_cast<std::size_t>(row * cost.nx + c);
  };
  const std::size_t s = pixel(j.at("start_node")), g = pixel(j.at("goal_node"));
  EXPECT_EQ(cost.bands[0].values[s], 0.0);
  EXPECT_EQ(cost.bands[1].values[g], 0.0);
  const double best = j.at("candidates")[0].at("cost_seconds").get<double>();
  EXPECT_NEAR(cost.bands[1].values[s], best, 1e-5 * best);
  EXPECT_NEAR(cost.bands[0].values[g], best, 1e-5 * best);
  EXPECT_EQ(cost.bands[2].values[s], 0.0);
  // GeoJSON per RFC 7946 (issue #40): longitude and latitude, the candidates' lattice paths in
  // EPSG:32613 kept as properties. The start node transformed here by GDAL on its own.
  const nlohmann::json geo = parse_json(read_text(dir + "/trajectory.geojson"), "geojson");
  EXPECT_EQ(geo.at("type"), "FeatureCollection");
  EXPECT_FALSE(geo.contains("crs"));  // RFC 7946 removed it: WGS 84 is implied
  EXPECT_NE(geo.at("projected_crs").get<std::string>().find("EPSG:32613"), std::string::npos);
  ASSERT_GE(geo.at("features").size(), 1u);
  const nlohmann::json& first = geo.at("features")[0];
  EXPECT_EQ(first.at("properties").at("kind"), "candidate");
  EXPECT_EQ(first.at("properties").at("projected_coordinates")[0][0], j.at("start_node")[0]);
  EXPECT_EQ(first.at("properties").at("projected_coordinates")[0][1], j.at("start_node")[1]);
  const auto [lon, lat] = gdal_test::utm_to_longitude_latitude(
      32613, j.at("start_node")[0].get<double>(), j.at("start_node")[1].get<double>());
  EXPECT_NEAR(first.at("geometry").at("coordinates")[0][0].get<double>(), lon, 1e-9);
  EXPECT_NEAR(first.at("geometry").at("coordinates")[0][1].get<double>(), lat, 1e-9);
  EXPECT_NEAR(lon, -104.3, 0.1);  // West Bijou, Colorado
  EXPECT_NEAR(lat, 39.5, 0.1);
  // GDAL's own GeoJSON driver reads it, and places the first vertex at the same point.
  const auto [feature_count, x0, y0] = gdal_test::first_vector_point(dir + "/trajectory.geojson");
  EXPECT_EQ(feature_count, static_cast<long long>(geo.at("features").size()));
  EXPECT_NEAR(x0, lon, 1e-9);
  EXPECT_NEAR(y0, lat, 1e-9);
  EXPECT_EQ(j.at("files").at("cost_to_go"), dir + "/cost_to_go.tif");
}

}  // namespace
}  // namespace talus::cli_test
