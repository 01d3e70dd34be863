// Where CEDD's blocks and their quadrants lie in a region, for each descriptor variant, and the
// per-channel pixel sums over them.
//
// A grid is described by its cells: the rectangles cut by `col_edges` x `row_edges`. Each block
// is made of up to four cells, its quadrants. Both variants' grids fit this form: LIRE's equal
// blocks have four distinct cells each; cedd-full's blocks one pixel wide (or tall) reuse one
// cell column (row) as both halves.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "core/descriptor/descriptor.h"

namespace orbit::cedd {

struct Grid {
  std::vector<int> col_edges;  // increasing x positions; cell column c spans [c, c+1)
  std::vector<int> row_edges;  // increasing y positions
  // Per block column bx: the cell columns of its left and right quadrants (equal when the
  // block is one pixel wide). Likewise per block row for the top and bottom quadrants.
  std::vector<int> left, right, top, bottom;

  int blocks_x() const { return static_cast<int>(left.size()); }
  int blocks_y() const { return static_cast<int>(top.size()); }
  int cell_cols() const { return static_cast<int>(col_edges.size()) - 1; }
  int cell_rows() const { return static_cast<int>(row_edges.size()) - 1; }
  bool empty() const { return left.empty() || top.empty(); }
};

// LIRE's grid for a width x height region (docs/design.md#grid): 40x40, 20x20 or 2x2-pixel
// blocks by the smaller side; pixels right of or below the last whole block are not covered.
// Empty when the region is 1 pixel wide or tall.
Grid LireGrid(int width, int height);

// cedd-full's grid: min(40, side) blocks along each side with edges at floor(i * side / n),
// each block split at its middle (integer halving), covering every pixel.
Grid FullGrid(int width, int height);

// Sums of B, G and R over every cell of `grid`, for a CV_8UC3 image that covers the grid.
// Layout: sums[(row * cell_cols + col) * 3 + channel], channel 0 = B, 1 = G, 2 = R.
std::vector<std::int64_t> CellSums(const cv::Mat& bgr, const Grid& grid);

}  // namespace orbit::cedd
