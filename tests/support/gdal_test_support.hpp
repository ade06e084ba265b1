// Raster fixtures made at test time with GDAL's C API (no gdal_translate
// needed): GeoTIFFs from a bundled .asc, small rasters with a chosen
// geotransform, CRS and NODATA, and reading a written raster's bands back.
#pragma once

#include <gtest/gtest.h>

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal.h>
#include <gdal_utils.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>

#include <array>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace talus::gdal_test {

inline void register_drivers() {
  static const bool done = [] {
    GDALAllRegister();
    return true;
  }();
  (void)done;
}

/// GDALTranslate(`source`) to `target` with gdal_translate's `args` (e.g.
/// {"-of", "GTiff", "-a_srs", "EPSG:32613"}); a failure if it fails.
inline void translate(const std::string& source, const std::string& target,
                      std::vector<std::string> args) {
  register_drivers();
  GDALDatasetH in = GDALOpen(source.c_str(), GA_ReadOnly);
  ASSERT_NE(in, nullptr) << source;
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  GDALTranslateOptions* options = GDALTranslateOptionsNew(argv.data(), nullptr);
  int usage_error = 0;
  GDALDatasetH out = GDALTranslate(target.c_str(), in, options, &usage_error);
  GDALTranslateOptionsFree(options);
  ASSERT_NE(out, nullptr) << CPLGetLastErrorMsg();
  GDALClose(out);
  GDALClose(in);
}

/// A one-band float64 GeoTIFF: `values` rows from the north (image order),
/// geotransform `gt`, CRS `srs` (e.g. "EPSG:4326"; empty = none), NODATA if given.
inline void write_raster(const std::string& path, int nx, int ny, const std::array<double, 6>& gt,
                         const std::string& srs, const std::vector<double>& values,
                         std::optional<double> nodata = std::nullopt) {
  register_drivers();
  ASSERT_EQ(values.size(), static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny));
  GDALDatasetH ds =
      GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), nx, ny, 1, GDT_Float64, nullptr);
  ASSERT_NE(ds, nullptr) << CPLGetLastErrorMsg();
  std::array<double, 6> t = gt;
  GDALSetGeoTransform(ds, t.data());
  if (!srs.empty()) {
    OGRSpatialReferenceH h = OSRNewSpatialReference(nullptr);
    ASSERT_EQ(OSRSetFromUserInput(h, srs.c_str()), OGRERR_NONE) << srs;
    char* wkt = nullptr;
    OSRExportToWkt(h, &wkt);
    GDALSetProjection(ds, wkt);
    CPLFree(wkt);
    OSRDestroySpatialReference(h);
  }
  GDALRasterBandH band = GDALGetRasterBand(ds, 1);
  if (nodata) GDALSetRasterNoDataValue(band, *nodata);
  std::vector<double> copy = values;
  ASSERT_EQ(GDALRasterIO(band, GF_Write, 0, 0, nx, ny, copy.data(), nx, ny, GDT_Float64, 0, 0),
            CE_None);
  GDALClose(ds);
}

/// A raster read back: size, geotransform, WKT, and per band its
/// description, NODATA and float64 values (image order).
struct ReadRaster {
  int nx = 0, ny = 0;
  std::array<double, 6> gt{};
  std::string wkt;
  std::string driver;
  struct Band {
    std::string description;
    std::optional<double> nodata;
    std::vector<double> values;
  };
  std::vector<Band> bands;
};

inline ReadRaster read_raster(const std::string& path) {
  register_drivers();
  ReadRaster out;
  GDALDatasetH ds = GDALOpen(path.c_str(), GA_ReadOnly);
  EXPECT_NE(ds, nullptr) << path;
  if (!ds) return out;
  out.nx = GDALGetRasterXSize(ds);
  out.ny = GDALGetRasterYSize(ds);
  GDALGetGeoTransform(ds, out.gt.data());
  out.wkt = GDALGetProjectionRef(ds);
  out.driver = GDALGetDriverShortName(GDALGetDatasetDriver(ds));
  for (int b = 1; b <= GDALGetRasterCount(ds); ++b) {
    GDALRasterBandH band = GDALGetRasterBand(ds, b);
    ReadRaster::Band entry;
    entry.description = GDALGetDescription(band);
    int has = 0;
    const double nd = GDALGetRasterNoDataValue(band, &has);
    if (has) entry.nodata = nd;
    entry.values.resize(static_cast<std::size_t>(out.nx) * static_cast<std::size_t>(out.ny));
    EXPECT_EQ(GDALRasterIO(band, GF_Read, 0, 0, out.nx, out.ny, entry.values.data(), out.nx, out.ny,
                           GDT_Float64, 0, 0),
              CE_None);
    out.bands.push_back(std::move(entry));
  }
  GDALClose(ds);
  return out;
}

/// The EPSG code GDAL identifies in `wkt`, or 0.
inline int epsg_of_wkt(const std::string& wkt) {
  OGRSpatialReferenceH h = OSRNewSpatialReference(nullptr);
  int code = 0;
  if (OSRSetFromUserInput(h, wkt.c_str()) == OGRERR_NONE) {
    OSRAutoIdentifyEPSG(h);
    const char* c = OSRGetAuthorityCode(h, nullptr);
    if (c) code = std::atoi(c);
  }
  OSRDestroySpatialReference(h);
  return code;
}

/// (longitude, latitude) [degrees] of (x, y) in the WGS 84 UTM zone `epsg`, by GDAL's OSR.
inline std::pair<double, double> utm_to_longitude_latitude(int epsg, double x, double y) {
  OGRSpatialReferenceH utm = OSRNewSpatialReference(nullptr),
                       wgs84 = OSRNewSpatialReference(nullptr);
  OSRImportFromEPSG(utm, epsg);
  OSRImportFromEPSG(wgs84, 4326);
  OSRSetAxisMappingStrategy(utm, OAMS_TRADITIONAL_GIS_ORDER);
  OSRSetAxisMappingStrategy(wgs84, OAMS_TRADITIONAL_GIS_ORDER);
  OGRCoordinateTransformationH t = OCTNewCoordinateTransformation(utm, wgs84);
  EXPECT_TRUE(t != nullptr && OCTTransform(t, 1, &x, &y, nullptr));
  OCTDestroyCoordinateTransformation(t);
  OSRDestroySpatialReference(utm);
  OSRDestroySpatialReference(wgs84);
  return {x, y};
}

/// A vector file opened by GDAL: its first layer's feature count and the first point of its
/// first feature's geometry.
inline std::tuple<long long, double, double> first_vector_point(const std::string& path) {
  GDALAllRegister();
  GDALDatasetH ds = GDALOpenEx(path.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr);
  EXPECT_NE(ds, nullptr) << path;
  if (ds == nullptr) return {0, 0.0, 0.0};
  OGRLayerH layer = GDALDatasetGetLayer(ds, 0);
  const long long count = OGR_L_GetFeatureCount(layer, 1);
  OGR_L_ResetReading(layer);
  OGRFeatureH feature = OGR_L_GetNextFeature(layer);
  double x = 0.0, y = 0.0;
  if (feature != nullptr) {
    OGRGeometryH g = OGR_F_GetGeometryRef(feature);
    if (g != nullptr && OGR_G_GetPointCount(g) > 0) {
      x = OGR_G_GetX(g, 0);
      y = OGR_G_GetY(g, 0);
    }
    OGR_F_Destroy(feature);
  }
  GDALClose(ds);
  return {count, x, y};
}

}  // namespace talus::gdal_test
