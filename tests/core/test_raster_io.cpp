// read_terrain through GDAL and write_geotiff (core/raster_io.hpp). Fixtures
// are made at test time with GDAL's C API from a bundled .asc.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "gdal_test_support.hpp"
#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/core/raster_io.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;

const std::string kWestBijou =
    std::string(TALUS_DATA_DIR) + "/terrain/west_bijou_escarpment_nasadem25m.asc";

fs::path scratch() {
  const fs::path dir = fs::temp_directory_path() / ("talus_raster_io_" + std::to_string(getpid()));
  fs::create_directories(dir);
  return dir;
}

/// The error message `read_terrain(path, options)` throws; a failure if it does not throw.
std::string read_error(const std::string& path, const TerrainReadOptions& options = {}) {
  try {
    read_terrain(path, options);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << path << " was accepted";
  return "";
}

void expect_contains(const std::string& text, const std::string& fragment) {
  EXPECT_NE(text.find(fragment), std::string::npos) << "'" << fragment << "' not in: " << text;
}

TEST(RasterIo, GdalIsAvailableInThisBuild) {
  EXPECT_TRUE(gdal_available());
}

TEST(RasterIo, AscIsReadByTheStrictReaderAndHasNoCrs) {
  const TerrainRaster t = read_terrain(kWestBijou);
  EXPECT_EQ(t.driver, "esri-ascii");
  EXPECT_FALSE(t.crs.known());
  EXPECT_EQ(t.grid.values(), read_esri_ascii(kWestBijou).values());
}

/// The bundled .asc (UTM 13N, see data/terrain/README.md) as a GeoTIFF written by GDAL loads to
/// the same grid: values bit for bit, the same node geometry, and the CRS it was given.
TEST(RasterIo, GeoTiffFromTheBundledAscLoadsToTheSameGrid) {
  const std::string tif = (scratch() / "west_bijou.tif").string();
  gdal_test::translate(kWestBijou, tif, {"-of", "GTiff", "-ot", "Float64", "-a_srs", "EPSG:32613"});
  const ElevationGrid asc = read_esri_ascii(kWestBijou);
  const TerrainRaster t = read_terrain(tif);
  EXPECT_EQ(t.driver, "GTiff");
  ASSERT_EQ(t.grid.ncols(), asc.ncols());
  ASSERT_EQ(t.grid.nrows(), asc.nrows());
  EXPECT_EQ(t.grid.cellsize(), asc.cellsize());
  EXPECT_EQ(t.grid.x_min(), asc.x_min());
  // y_min goes through the north edge and back: a few ulp of 4.4e6 m.
  EXPECT_NEAR(t.grid.y_min(), asc.y_min(), 1e-8);
  EXPECT_EQ(t.grid.values(), asc.values());  // bit-equal
  EXPECT_EQ(t.grid.void_count(), 0u);
  ASSERT_TRUE(t.crs.epsg.has_value());
  EXPECT_EQ(*t.crs.epsg, 32613);
  expect_contains(t.crs.name, "UTM zone 13N");
  EXPECT_FALSE(t.reprojected);
}

TEST(RasterIo, AscTakesItsCrsFromAPrjBesideIt) {
  const fs::path dir = scratch() / "prj";
  fs::create_directories(dir);
  fs::copy_file(kWestBijou, dir / "dem.asc", fs::copy_options::overwrite_existing);
  std::ofstream(dir / "dem.prj") << "EPSG:32613\n";
  const TerrainRaster t = read_terrain((dir / "dem.asc").string());
  EXPECT_EQ(t.driver, "esri-ascii");
  ASSERT_TRUE(t.crs.epsg.has_value());
  EXPECT_EQ(*t.crs.epsg, 32613);
  std::ofstream(dir / "dem.prj") << "not a CRS\n";
  expect_contains(read_error((dir / "dem.asc").string()), "dem.prj: not a coordinate reference");
}

/// A VRT of one band of 10 x 10 pixels whose source is `source_xml` (the <SourceFilename>
/// element), with extra band attributes, band elements (Scale, Offset, UnitType) and type.
std::string write_vrt(const fs::path& file, const std::string& source_xml,
                      const std::string& band_attributes = "",
                      const std::string& band_elements = "",
                      const std::string& data_type = "Float64") {
  std::ofstream(file) << "<VRTDataset rasterXSize=\"10\" rasterYSize=\"10\">\n"
                         "  <SRS>EPSG:32613</SRS>\n"
                         "  <GeoTransform>557000, 30, 0, 4373500, 0, -30</GeoTransform>\n"
                         "  <VRTRasterBand dataType=\""
                      << data_type << "\" band=\"1\"" << band_attributes << ">\n    "
                      << band_elements << "\n    <SimpleSource>\n      " << source_xml
                      << "\n      <SourceBand>1</SourceBand>\n    </SimpleSource>\n"
                         "  </VRTRasterBand>\n</VRTDataset>\n";
  return file.string();
}

// Issue #39 item 3: a VRT reaches other files. A FIFO among its sources hung GDAL; /dev/zero,
// /vsigzip/ and raw bands were followed. Each is refused with one line before GDAL opens
// the VRT; a VRT over a regular GeoTIFF still reads, equal to the GeoTIFF.
TEST(RasterIo, AVrtIsReadOnlyWhenEverySourceIsARegularFile) {
  const fs::path dir = scratch() / "vrt";
  fs::create_directories(dir);
  const std::string tif = (dir / "src.tif").string();
  gdal_test::translate(
      kWestBijou, tif,
      {"-of", "GTiff", "-ot", "Float64", "-a_srs", "EPSG:32613", "-srcwin", "0", "0", "10", "10"});
  const TerrainRaster direct = read_terrain(tif);
  const TerrainRaster via = read_terrain(
      write_vrt(dir / "good.vrt", "<SourceFilename relativeToVRT=\"1\">src.tif</SourceFilename>"));
  EXPECT_EQ(via.driver, "VRT");
  EXPECT_EQ(via.grid.values(), direct.grid.values());

  const fs::path fifo = dir / "src.fifo";
  fs::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  expect_contains(read_error(write_vrt(dir / "fifo.vrt",
                                       "<SourceFilename relativeToVRT=\"1\">src.fifo"
                                       "</SourceFilename>")),
                  "is not a regular file");
  expect_contains(
      read_error(write_vrt(dir / "zero.vrt", "<SourceFilename>/dev/zero</SourceFilename>")),
      "is not a regular file");
  expect_contains(read_error(write_vrt(dir / "gzip.vrt",
                                       "<SourceFilename>/vsigzip/" + tif + "</SourceFilename>")),
                  "GDAL virtual path or a URL");
  expect_contains(
      read_error(write_vrt(dir / "url.vrt",
                           "<SourceFilename>https://example.org/dem.tif</SourceFilename>")),
      "GDAL virtual path or a URL");
  expect_contains(
      read_error(write_vrt(dir / "raw.vrt", "<SourceFilename>" + tif + "</SourceFilename>",
                           " subClass=\"VRTRawRasterBand\"")),
      "raw raster band");
  // A tile-service description is no terrain file: the WMS driver is not among those allowed.
  std::ofstream(dir / "wms.xml") << "<GDAL_WMS><Service name=\"TMS\"><ServerUrl>"
                                    "https://example.org/${z}/${x}/${y}.png</ServerUrl></Service>"
                                    "<DataWindow><UpperLeftX>0</UpperLeftX></DataWindow>"
                                    "</GDAL_WMS>\n";
  expect_contains(read_error((dir / "wms.xml").string()), "not a raster GDAL can read");
}

/// A VRT of `tif`'s 10 x 10 pixels as one band of `data_type` with `band_elements` (Scale,
/// Offset, UnitType) inside the band.
std::string write_band_vrt(const fs::path& file, const std::string& tif,
                           const std::string& band_elements,
                           const std::string& data_type = "Float64") {
  return write_vrt(file, "<SourceFilename>" + tif + "</SourceFilename>", "", band_elements,
                   data_type);
}

// Issue #39 item 3: a band's scale, offset and unit were ignored (an int16 DEM with scale 0.1
// and offset 1000 read as 0-1190 m), a complex band read as its real part.
TEST(RasterIo, ABandsScaleOffsetAndUnitGiveElevationsInMetres) {
  const fs::path dir = scratch() / "scaled";
  fs::create_directories(dir);
  const std::string tif = (dir / "src.tif").string();
  gdal_test::translate(
      kWestBijou, tif,
      {"-of", "GTiff", "-ot", "Float64", "-a_srs", "EPSG:32613", "-srcwin", "0", "0", "10", "10"});
  const std::vector<double> raw = read_terrain(tif).grid.values();
  const auto expect_mapped = [&](const TerrainRaster& r, double scale, double offset) {
    ASSERT_EQ(r.grid.values().size(), raw.size());
    for (std::size_t k = 0; k < raw.size(); ++k)
      ASSERT_NEAR(r.grid.values()[k], raw[k] * scale + offset, 1e-9 * std::abs(raw[k] + offset));
  };
  expect_mapped(read_terrain(write_band_vrt(dir / "scaled.vrt", tif,
                                            "<Offset>1000</Offset><Scale>0.1</Scale>")),
                0.1, 1000.0);
  expect_mapped(read_terrain(write_band_vrt(dir / "feet.vrt", tif, "<UnitType>ft</UnitType>")),
                0.3048, 0.0);
  expect_mapped(read_terrain(write_band_vrt(dir / "metres.vrt", tif, "<UnitType>m</UnitType>")),
                1.0, 0.0);
  expect_contains(read_error(write_band_vrt(dir / "celsius.vrt", tif, "<UnitType>degC</UnitType>")),
                  "unit is 'degC'");
  expect_contains(read_error(write_band_vrt(dir / "zero.vrt", tif, "<Scale>0</Scale>")), "scale 0");
  expect_contains(read_error(write_band_vrt(dir / "complex.vrt", tif, "", "CFloat64")),
                  "complex numbers");
}

/// Pixel (c, r from the north) of a 5 x 4 raster; NODATA -32768 at three pixels, NaN at one.
TEST(RasterIo, NodataGeoTiffKeepsItsMask) {
  const int nx = 5, ny = 4;
  std::vector<double> values(nx * ny);
  for (int k = 0; k < nx * ny; ++k) values[k] = 100.0 + k;
  values[0] = -32768.0;                                           // north-west corner
  values[2 * nx + 3] = -32768.0;                                  // c 3, r 2
  values[3 * nx + 4] = -32768.0;                                  // south-east corner
  values[1 * nx + 1] = std::numeric_limits<double>::quiet_NaN();  // c 1, r 1
  const std::string tif = (scratch() / "nodata.tif").string();
  gdal_test::write_raster(tif, nx, ny, {1000.0, 2.0, 0.0, 5008.0, 0.0, -2.0}, "EPSG:32613", values,
                          -32768.0);
  const TerrainRaster t = read_terrain(tif);
  EXPECT_EQ(t.grid.void_count(), 4u);
  for (int r = 0; r < ny; ++r) {
    for (int c = 0; c < nx; ++c) {
      const std::size_t i = static_cast<std::size_t>(c), j = static_cast<std::size_t>(ny - 1 - r);
      const double v = values[r * nx + c];
      const bool hole = std::isnan(v) || v == -32768.0;
      EXPECT_EQ(t.grid.valid(i, j), !hole) << c << ", " << r;
      if (!hole) {
        EXPECT_EQ(t.grid.at(i, j), v);
      }
    }
  }
  EXPECT_EQ(t.grid.x_min(), 1001.0);
  EXPECT_EQ(t.grid.y_min(), 5001.0);
  EXPECT_EQ(t.grid.cellsize(), 2.0);
}

TEST(RasterIo, SouthUpRowsAreFlipped) {
  const std::string tif = (scratch() / "south_up.tif").string();
  gdal_test::write_raster(tif, 2, 3, {0.0, 1.0, 0.0, 10.0, 0.0, 1.0}, "", {1, 2, 3, 4, 5, 6});
  const TerrainRaster t = read_terrain(tif);
  EXPECT_EQ(t.grid.y_min(), 10.5);
  EXPECT_EQ(t.grid.at(0, 0), 1.0);  // first row is the southern one
  EXPECT_EQ(t.grid.at(1, 2), 6.0);
  EXPECT_FALSE(t.crs.known());
}

/// A 0.01° x 0.01° DEM near West Bijou (39.5 N, 104.3 W): elevation 1700 + 1000 (lon + 104.3).
std::string geographic_raster() {
  const int nx = 41, ny = 31;
  const double dx = 0.01 / (nx - 1) * 1.0, lon0 = -104.305, lat1 = 39.505;
  std::vector<double> values;
  for (int r = 0; r < ny; ++r) {
    for (int c = 0; c < nx; ++c)
      values.push_back(1700.0 + 1000.0 * (lon0 + (c + 0.5) * dx + 104.3));
  }
  const std::string tif = (scratch() / "geographic.tif").string();
  gdal_test::write_raster(tif, nx, ny, {lon0, dx, 0.0, lat1, 0.0, -dx}, "EPSG:4326", values);
  return tif;
}

// Issue #39 item 4: `--reproject auto` on a strip round the pole warped to 7190 x 7190 pixels
// (1.3 GB) before anything checked the size. The warp's output is sized first, within the
// memory budget and a growth of 16 times the source, and refused with one line.
TEST(RasterIo, AWarpBeyondTheMemoryBudgetIsRefusedBeforeWarping) {
  const int nx = 3600, ny = 2;
  const std::vector<double> values(static_cast<std::size_t>(nx * ny), 100.0);
  const std::string tif = (scratch() / "polar_strip.tif").string();
  gdal_test::write_raster(tif, nx, ny, {-180.0, 0.1, 0.0, 89.9, 0.0, -0.1}, "EPSG:4326", values);
  ::setenv("TALUS_MEMORY_LIMIT_MB", "64", 1);
  TerrainReadOptions options;
  options.reproject = Reprojection::kAuto;
  const auto t0 = std::chrono::steady_clock::now();
  const std::string message = read_error(tif, options);
  ::unsetenv("TALUS_MEMORY_LIMIT_MB");
  expect_contains(message, "warped to EPSG:32631");
  // Within any budget the strip would grow from 7200 pixels to 10785 x 10785 (2.8 GB, 24 s).
  ::unsetenv("TALUS_MEMORY_LIMIT_MB");
  expect_contains(read_error(tif, options), "would grow from 7200 to");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0);
}

// A command that fits a surface budgets the fit with the read, so an 8000 x 8000 DEM it could
// not fit is refused before its pixels are read (it was read at 1.2 GB, then ran out of memory).
TEST(RasterIo, TheCallersWorkPerNodeIsBudgetedBeforeThePixelsAreRead) {
  const int n = 1500;
  const std::string tif = (scratch() / "large.tif").string();
  gdal_test::write_raster(tif, n, n, {0.0, 1.0, 0.0, 1500.0, 0.0, -1.0}, "EPSG:32613",
                          std::vector<double>(static_cast<std::size_t>(n) * n, 10.0));
  ::setenv("TALUS_MEMORY_LIMIT_MB", "64", 1);
  TerrainReadOptions options;  // 17 bytes a pixel: 36 MiB
  std::string read_alone;
  try {
    read_alone = read_terrain(tif, options).brief_report();
  } catch (const InputError& e) {
    read_alone = std::string("refused: ") + e.what();
  }
  options.bytes_per_node_after = 48.0;  // and a fit: 140 MiB
  const std::string with_fit = read_error(tif, options);
  ::unsetenv("TALUS_MEMORY_LIMIT_MB");
  EXPECT_EQ(read_alone.find("refused"), std::string::npos) << read_alone;
  expect_contains(with_fit, "(1500 x 1500 pixels, read and fitted)");
  options.bytes_per_node_after = -1.0;
  expect_contains(read_error(tif, options), "bytes_per_node_after");
}

TEST(RasterIo, GeographicRasterIsRefusedWithoutReprojection) {
  const std::string message = read_error(geographic_raster());
  expect_contains(message, "geographic (degrees)");
  expect_contains(message, "EPSG:4326");
  expect_contains(message, "--reproject auto");
  expect_contains(message, "EPSG:32613");  // the zone it would use
}

TEST(RasterIo, GeographicRasterReprojectsToTheUtmZoneOfItsCentre) {
  TerrainReadOptions options;
  options.reproject = Reprojection::kAuto;
  const TerrainRaster t = read_terrain(geographic_raster(), options);
  EXPECT_TRUE(t.reprojected);
  ASSERT_TRUE(t.crs.epsg && t.source_crs.epsg);
  EXPECT_EQ(*t.crs.epsg, 32613);
  EXPECT_EQ(*t.source_crs.epsg, 4326);
  // 0.01° of longitude at 39.5 N is 858 m, of latitude 1111 m; 41 x 31 pixels of about 21-27 m.
  const double width = t.grid.x_max() - t.grid.x_min(), height = t.grid.y_max() - t.grid.y_min();
  EXPECT_GT(width, 700.0);
  EXPECT_LT(width, 900.0);
  EXPECT_GT(height, 700.0);
  EXPECT_LT(height, 900.0);
  EXPECT_GT(t.grid.cellsize(), 15.0);
  EXPECT_LT(t.grid.cellsize(), 30.0);
  // UTM 13N eastings near 104.3 W (central meridian 105 W) are about 560 km, northings 4370 km.
  EXPECT_NEAR(t.grid.x_min(), 560e3, 5e3);
  EXPECT_NEAR(t.grid.y_min(), 4372e3, 5e3);
  // The elevations stay in the source's range (bilinear), and some valid nodes exist.
  const auto range = t.grid.elevation_range();
  ASSERT_TRUE(range);
  // Source pixels span 1700 + 1000 (-0.005 + (c + 0.5) 0.00025), c = 0 .. 40.
  EXPECT_GE(range->first, 1695.125 - 1e-9);
  EXPECT_LE(range->second, 1705.125 + 1e-9);
  EXPECT_GT(range->second - range->first, 5.0);
  EXPECT_LT(t.grid.void_count(), t.grid.ncols() * t.grid.nrows() / 2);
}

TEST(RasterIo, RotatedAndNonSquareRastersAreRefused) {
  const std::string rotated = (scratch() / "rotated.tif").string();
  gdal_test::write_raster(rotated, 3, 3, {0.0, 1.0, 0.2, 10.0, 0.2, -1.0}, "EPSG:32613",
                          std::vector<double>(9, 1.0));
  const std::string m = read_error(rotated);
  expect_contains(m, "rotated.tif: the raster is rotated");
  EXPECT_EQ(m.find('\n'), std::string::npos);
  const std::string oblong = (scratch() / "oblong.tif").string();
  gdal_test::write_raster(oblong, 3, 3, {0.0, 1.0, 0.0, 10.0, 0.0, -2.0}, "EPSG:32613",
                          std::vector<double>(9, 1.0));
  expect_contains(read_error(oblong), "non-square pixels (1 x 2)");
}

TEST(RasterIo, BadInputsGiveOneClearLine) {
  expect_contains(read_error((scratch() / "missing.tif").string()), "missing.tif: no such file");
  const std::string text = (scratch() / "text.tif").string();
  std::ofstream(text) << "hello\n";
  expect_contains(read_error(text), "text.tif: not a raster GDAL can read");
  const std::string feet = (scratch() / "feet.tif").string();
  gdal_test::write_raster(feet, 3, 3, {0.0, 1.0, 0.0, 10.0, 0.0, -1.0}, "EPSG:2232",
                          std::vector<double>(9, 1.0));
  expect_contains(read_error(feet), "not metres");
  const std::string metric = (scratch() / "metric.tif").string();
  gdal_test::write_raster(metric, 3, 3, {0.0, 1.0, 0.0, 10.0, 0.0, -1.0}, "EPSG:32613",
                          std::vector<double>(9, 1.0));
  TerrainReadOptions band;
  band.band = 2;
  expect_contains(read_error(metric, band), "band 2 requested, the raster has 1");
  const std::string huge = (scratch() / "huge.tif").string();
  gdal_test::write_raster(huge, 2, 2, {0.0, 1.0, 0.0, 10.0, 0.0, -1.0}, "",
                          {1.0, -3.4e38, 1.0, 1.0});
  expect_contains(read_error(huge), "beyond the supported elevation magnitude");
}

TEST(RasterIo, WrittenGeoTiffHasTheGridBandsNamesAndNodata) {
  ElevationGrid grid(4, 3, 2.5, 100.0, 200.0);
  GeoReference crs;
  crs.wkt = read_terrain([] {
              const std::string tif = (scratch() / "crs.tif").string();
              gdal_test::write_raster(tif, 2, 2, {0.0, 1.0, 0.0, 2.0, 0.0, -1.0}, "EPSG:32613",
                                      {1, 2, 3, 4});
              return tif;
            }())
                .crs.wkt;
  RasterLayers layers = RasterLayers::on_grid_of(grid, crs);
  std::vector<double> a(12), b(12, 0.5);
  for (std::size_t k = 0; k < 12; ++k) a[k] = 0.25 * static_cast<double>(k);
  a[5] = std::numeric_limits<double>::quiet_NaN();
  b[7] = std::numeric_limits<double>::infinity();
  layers.bands.push_back({"first", a, "", {{"heading_deg", "0"}}});
  layers.bands.push_back({"second", b, "m/s", {}});
  const std::string out = (scratch() / "layers.tif").string();
  write_geotiff(layers, out);
  const gdal_test::ReadRaster r = gdal_test::read_raster(out);
  EXPECT_EQ(r.driver, "GTiff");
  ASSERT_EQ(r.nx, 4);
  ASSERT_EQ(r.ny, 3);
  EXPECT_EQ(r.gt[0], 98.75);
  EXPECT_EQ(r.gt[1], 2.5);
  EXPECT_EQ(r.gt[3], 206.25);
  EXPECT_EQ(r.gt[5], -2.5);
  EXPECT_EQ(gdal_test::epsg_of_wkt(r.wkt), 32613);
  ASSERT_EQ(r.bands.size(), 2u);
  EXPECT_EQ(r.bands[0].description, "first");
  EXPECT_EQ(r.bands[1].description, "second");
  for (std::size_t band = 0; band < 2; ++band) {
    ASSERT_TRUE(r.bands[band].nodata);
    EXPECT_EQ(*r.bands[band].nodata, -9999.0);
    const std::vector<double>& source = band == 0 ? a : b;
    for (std::size_t row = 0; row < 3; ++row) {
      for (std::size_t i = 0; i < 4; ++i) {
        const double v = r.bands[band].values[row * 4 + i];
        const double expected = source[(2 - row) * 4 + i];
        if (std::isnan(expected)) {
          EXPECT_EQ(v, -9999.0);
        } else {
          EXPECT_EQ(v, static_cast<double>(static_cast<float>(expected)));
        }
      }
    }
  }
  // Read back as a terrain: two bands, so which holds the elevations must be said; band 2's
  // unit (m/s) is no length; band 1 is the same node geometry.
  expect_contains(read_error(out), "the raster has 2 bands");
  TerrainReadOptions choose;
  choose.band = 2;
  expect_contains(read_error(out, choose), "unit is 'm/s'");
  choose.band = 1;
  const TerrainRaster back = read_terrain(out, choose);
  EXPECT_EQ(back.grid.x_min(), 100.0);
  EXPECT_EQ(back.grid.y_min(), 200.0);
  EXPECT_EQ(back.grid.void_count(), 1u);
  EXPECT_FALSE(back.grid.valid(1, 1));  // a[5]: column 1, row 1 from the south
  // No temporary file is left beside it.
  for (const auto& entry : fs::directory_iterator(scratch())) {
    EXPECT_EQ(entry.path().filename().string().find(".talus-tmp-"), std::string::npos);
  }
}

TEST(RasterIo, InvalidLayersAreRefusedAndNothingIsWritten) {
  ElevationGrid grid(3, 3, 1.0, 0.0, 0.0);
  RasterLayers layers = RasterLayers::on_grid_of(grid, {});
  const std::string out = (scratch() / "never.tif").string();
  EXPECT_THROW(write_geotiff(layers, out), InputError);  // no band
  layers.bands.push_back({"short", std::vector<double>(8, 1.0), "", {}});
  EXPECT_THROW(write_geotiff(layers, out), InputError);
  layers.bands[0].values.assign(9, -9999.0);  // a value equal to NODATA
  EXPECT_THROW(write_geotiff(layers, out), InputError);
  layers.bands[0].values.assign(9, 1.0);
  EXPECT_THROW(write_geotiff(layers, (scratch() / "no_such_dir" / "x.tif").string()), InputError);
  EXPECT_FALSE(fs::exists(out));
}

TEST(RasterIo, ReprojectionParsesNoneAndAuto) {
  EXPECT_EQ(parse_reprojection("none"), Reprojection::kNone);
  EXPECT_EQ(parse_reprojection("auto"), Reprojection::kAuto);
  EXPECT_THROW(parse_reprojection("utm"), InputError);
  EXPECT_EQ(to_string(Reprojection::kAuto), "auto");
}

}  // namespace
}  // namespace talus
