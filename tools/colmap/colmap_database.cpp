#include "tools/colmap/colmap_database.h"

#include <sqlite3.h>

#include <cmath>
#include <memory>
#include <stdexcept>

namespace lc2wf {
namespace {

struct CloseDatabase {
  void operator()(sqlite3* db) const { sqlite3_close(db); }
};
struct FinalizeStatement {
  void operator()(sqlite3_stmt* s) const { sqlite3_finalize(s); }
};

std::string text_column(sqlite3_stmt* s, int col) {
  const unsigned char* t = sqlite3_column_text(s, col);
  return t ? std::string(reinterpret_cast<const char*>(t), static_cast<size_t>(sqlite3_column_bytes(s, col))) : std::string();
}

}  // namespace

std::vector<ImageDescriptors> read_colmap_descriptors(const std::filesystem::path& database) {
  const std::string where = database.string();
  if (!std::filesystem::is_regular_file(database)) throw std::runtime_error(where + ": COLMAP database not found");
  sqlite3* raw = nullptr;
  // Read-only: the database belongs to the COLMAP run and must not be changed by reading it.
  const int opened = sqlite3_open_v2(where.c_str(), &raw, SQLITE_OPEN_READONLY, nullptr);
  std::unique_ptr<sqlite3, CloseDatabase> db(raw);
  if (opened != SQLITE_OK) throw std::runtime_error(where + ": cannot open the COLMAP database: " + sqlite3_errstr(opened));
  const char* query =
      "SELECT images.image_id, images.name, descriptors.rows, descriptors.cols, descriptors.data FROM images "
      "JOIN descriptors ON images.image_id = descriptors.image_id ORDER BY images.name";
  sqlite3_stmt* raw_stmt = nullptr;
  if (sqlite3_prepare_v2(db.get(), query, -1, &raw_stmt, nullptr) != SQLITE_OK)
    throw std::runtime_error(where + ": not a COLMAP database with images and descriptors: " + sqlite3_errmsg(db.get()));
  std::unique_ptr<sqlite3_stmt, FinalizeStatement> stmt(raw_stmt);
  std::vector<ImageDescriptors> images;
  int step;
  while ((step = sqlite3_step(stmt.get())) == SQLITE_ROW) {
    ImageDescriptors im;
    im.image_id = sqlite3_column_int64(stmt.get(), 0);
    im.name = text_column(stmt.get(), 1);
    im.rows = sqlite3_column_int64(stmt.get(), 2);
    const int64_t cols = sqlite3_column_int64(stmt.get(), 3);
    const int64_t bytes = sqlite3_column_bytes(stmt.get(), 4);
    const std::string image = where + ": image '" + im.name + "'";
    if (cols != kSiftDimensions && !(im.rows == 0 && cols == 0))
      throw std::runtime_error(image + ": descriptors have " + std::to_string(cols) + " columns, expected 128");
    // Checked against the blob's size before anything is allocated: rows comes from the file.
    if (im.rows < 0 || bytes != im.rows * cols)
      throw std::runtime_error(image + ": descriptor blob holds " + std::to_string(bytes) + " bytes for " +
                               std::to_string(im.rows) + " rows");
    const auto* data = static_cast<const uint8_t*>(sqlite3_column_blob(stmt.get(), 4));
    im.descriptors.resize(static_cast<size_t>(im.rows * kSiftDimensions));
    for (int64_t r = 0; r < im.rows; ++r) {
      float* row = im.descriptors.data() + r * kSiftDimensions;
      double norm = 0;
      for (int c = 0; c < kSiftDimensions; ++c) {
        row[c] = static_cast<float>(data[r * kSiftDimensions + c]);
        norm += static_cast<double>(row[c]) * row[c];
      }
      if (norm > 0)
        for (int c = 0; c < kSiftDimensions; ++c) row[c] = static_cast<float>(row[c] / std::sqrt(norm));
    }
    images.push_back(std::move(im));
  }
  if (step != SQLITE_DONE) throw std::runtime_error(where + ": reading descriptors failed: " + sqlite3_errmsg(db.get()));
  return images;
}

}  // namespace lc2wf
