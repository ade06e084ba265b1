// The `talus` CLI against rasters that would exhaust the memory or be read wrongly (issue
// 39's GDAL families): each is refused with one line before a pixel is read, under the
// robustness suite's memory cap and time limit (cli_robustness_support.hpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_robustness_support.hpp"
#include "cli_test_support.hpp"
#include "gdal_test_support.hpp"

namespace talus::cli_test {
namespace {

/// A VRT of `tif` (a 10 x 10 raster) as one band of `data_type` with `band_elements`; in
/// degrees (EPSG:4326) or metres (EPSG:32613).
std::string band_vrt(const std::string& name, const std::string& tif,
                     const std::string& band_elements, bool degrees,
                     const std::string& data_type = "Float64") {
  const std::string file = scratch_file(name);
  std::ofstream(file) << "<VRTDataset rasterXSize=\"10\" rasterYSize=\"10\">\n"
                      << (degrees ? "  <SRS>EPSG:4326</SRS>\n  <GeoTransform>-104.3, 0.001, 0, "
                                    "39.5, 0, -0.001</GeoTransform>\n"
                                  : "  <SRS>EPSG:32613</SRS>\n  <GeoTransform>557000, 30, 0, "
                                    "4373500, 0, -30</GeoTransform>\n")
                      << "  <VRTRasterBand dataType=\"" << data_type << "\" band=\"1\">\n    "
                      << band_elements << "\n    <SimpleSource><SourceFilename>" << tif
                      << "</SourceFilename><SourceBand>1</SourceBand></SimpleSource>\n"
                         "  </VRTRasterBand>\n</VRTDataset>\n";
  return file;
}

TEST(CliRobustness, RastersTooLargeOrWronglyDescribedAreRefusedBeforeAPixelIsRead) {
  // A strip round the pole, 3600 x 2 pixels, warps to 10785 x 10785.
  const std::string polar = scratch_file("robust_polar.tif");
  gdal_test::write_raster(polar, 3600, 2, {-180.0, 0.1, 0.0, 89.9, 0.0, -0.1}, "EPSG:4326",
                          std::vector<double>(7200, 100.0));
  // 2600 x 2600 pixels: 17 bytes each to read and 48 to fit, beyond the suite's 384 MiB.
  const int n = 2600;
  const std::string large = scratch_file("robust_large.tif");
  gdal_test::write_raster(large, n, n, {0.0, 1.0, 0.0, n, 0.0, -1.0}, "EPSG:32613",
                          std::vector<double>(static_cast<std::size_t>(n) * n, 10.0));
  const std::string small = scratch_file("robust_small.tif");
  gdal_test::write_raster(small, 10, 10, {-104.3, 0.001, 0.0, 39.5, 0.0, -0.001}, "EPSG:4326",
                          std::vector<double>(100, 1700.0));
  const std::string metric = scratch_file("robust_metric.tif");
  gdal_test::write_raster(metric, 10, 10, {557000.0, 30.0, 0.0, 4373500.0, 0.0, -30.0},
                          "EPSG:32613", std::vector<double>(100, 1700.0));
  const std::string two_bands = scratch_file("robust_two_bands.tif");
  gdal_test::translate(metric, two_bands, {"-of", "GTiff", "-b", "1", "-b", "1"});
  const std::string out = scratch_file("robust_raster_plan");
  const std::string vehicle = point_mass_vehicle("robust_raster_v.yaml", 0.7, 10.0);
  expect_refused(
      {{"polar warp", "terrain info --reproject auto " + quoted(polar), "would grow from 7200 to"},
       {"fit beyond the budget",
        "plan --terrain " + quoted(large) + " --vehicle " + quoted(vehicle) +
            " --start 10,10 --goal 2500,2500 --out " + quoted(out),
        "(2600 x 2600 pixels, read and fitted)"},
       {"several bands", "terrain info " + quoted(two_bands), "the raster has 2 bands"},
       {"a band beyond the raster's", "terrain info --band 3 " + quoted(two_bands),
        "band 3 requested, the raster has 2"},
       {"scaled band warped",
        "terrain info --reproject auto " +
            quoted(band_vrt("robust_scaled.vrt", small, "<Scale>0.1</Scale>", true)),
        "does not carry through the warp"},
       {"unit not a length",
        "terrain info " +
            quoted(band_vrt("robust_degc.vrt", metric, "<UnitType>degC</UnitType>", false)),
        "unit is 'degC'"},
       {"complex band",
        "terrain info " + quoted(band_vrt("robust_complex.vrt", metric, "", false, "CFloat64")),
        "complex numbers"}},
      out);
}

}  // namespace
}  // namespace talus::cli_test
