#include "core/descriptor/cedd_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/base/cpu_dispatch.h"
#include "core/descriptor/column_sums.h"

namespace orbit::cedd {
namespace {

// Fills edges and the two half-block cell indices for equal blocks of `step` pixels (even).
void EqualBlocks(int blocks, int step, std::vector<int>& edges, std::vector<int>& first,
                 std::vector<int>& second) {
  for (int b = 0; b < blocks; ++b) {
    edges.push_back(b * step);
    edges.push_back(b * step + step / 2);
    first.push_back(2 * b);
    second.push_back(2 * b + 1);
  }
  edges.push_back(blocks * step);
}

// Blocks with edges at floor(i * size / n); a block of one pixel is its own both halves.
void ProportionalBlocks(int size, std::vector<int>& edges, std::vector<int>& first,
                        std::vector<int>& second) {
  const int n = std::min(40, size);
  edges.push_back(0);
  for (int b = 0; b < n; ++b) {
    const int begin = static_cast<int>(static_cast<std::int64_t>(b) * size / n);
    const int end = static_cast<int>(static_cast<std::int64_t>(b + 1) * size / n);
    const int cell = static_cast<int>(edges.size()) - 1;
    if (end - begin >= 2) {
      edges.push_back(begin + (end - begin) / 2);
      first.push_back(cell);
      second.push_back(cell + 1);
    } else {
      first.push_back(cell);
      second.push_back(cell);
    }
    edges.push_back(end);
  }
}

// Adds the image rows [y0, y1) into acc (one entry per byte of a row), then adds acc's runs
// between col_edges into the sums of one row of cells. Acc is wide enough not to overflow:
// uint16 holds up to 257 rows of 255.
template <typename Acc>
void SumCellRow(const cv::Mat& bgr, int y0, int y1, const std::vector<int>& col_edges,
                std::int64_t* sums) {
  const int bytes = col_edges.back() * 3;
  std::vector<Acc> acc(bytes, 0);
  for (int y = y0; y < y1; ++y) {
    RunHotLoop<AddRowToColumnSums<Acc>>(bgr.ptr<std::uint8_t>(y), acc.data(),
                                        static_cast<std::size_t>(bytes));
  }
  const int cols = static_cast<int>(col_edges.size()) - 1;
  for (int c = 0; c < cols; ++c) {
    std::int64_t b = 0, g = 0, r = 0;
    for (int x = col_edges[c]; x < col_edges[c + 1]; ++x) {
      b += acc[3 * x];
      g += acc[3 * x + 1];
      r += acc[3 * x + 2];
    }
    sums[3 * c] = b;
    sums[3 * c + 1] = g;
    sums[3 * c + 2] = r;
  }
}

}  // namespace

Grid LireGrid(int width, int height) {
  Grid grid;
  const int m = std::min(width, height);
  int blocks_side = -1;
  if (m >= 80)
    blocks_side = 40;  // N = 1600
  else if (m >= 40)
    blocks_side = 20;  // N = 400
  int step_x = 2, step_y = 2, max_x, max_y;
  if (blocks_side > 0) {
    step_x = width / blocks_side;
    step_y = height / blocks_side;
    if (step_x % 2 != 0) --step_x;
    if (step_y % 2 != 0) --step_y;
    max_x = step_x * blocks_side;
    max_y = step_y * blocks_side;
  } else {
    max_x = 2 * (width / 2);
    max_y = 2 * (height / 2);
  }
  const int blocks_x = max_x / step_x, blocks_y = max_y / step_y;
  if (blocks_x == 0 || blocks_y == 0) return grid;
  EqualBlocks(blocks_x, step_x, grid.col_edges, grid.left, grid.right);
  EqualBlocks(blocks_y, step_y, grid.row_edges, grid.top, grid.bottom);
  return grid;
}

Grid FullGrid(int width, int height) {
  Grid grid;
  if (width <= 0 || height <= 0) return grid;
  ProportionalBlocks(width, grid.col_edges, grid.left, grid.right);
  ProportionalBlocks(height, grid.row_edges, grid.top, grid.bottom);
  return grid;
}

std::vector<std::int64_t> CellSums(const cv::Mat& bgr, const Grid& grid) {
  const int cols = grid.cell_cols(), rows = grid.cell_rows();
  std::vector<std::int64_t> sums(static_cast<std::size_t>(rows) * cols * 3, 0);
  constexpr int kMaxRowsUint16 = std::numeric_limits<std::uint16_t>::max() / 255;
  for (int r = 0; r < rows; ++r) {
    const int y0 = grid.row_edges[r], y1 = grid.row_edges[r + 1];
    std::int64_t* out = sums.data() + static_cast<std::size_t>(r) * cols * 3;
    if (y1 - y0 <= kMaxRowsUint16) {
      SumCellRow<std::uint16_t>(bgr, y0, y1, grid.col_edges, out);
    } else {
      SumCellRow<std::uint32_t>(bgr, y0, y1, grid.col_edges, out);
    }
  }
  return sums;
}

}  // namespace orbit::cedd
