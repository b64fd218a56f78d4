// Tall matrices (n rows, a few dozen to a few hundred columns) stored by panels of kPanelRows
// rows, column-major inside a panel: the layout of the Lanczos basis and its blocks. Kernels run
// down a column of a panel with aligned SSE2 loads (two rows per register), and a panel of the
// basis stays in L2 while every column of it is used. Rows past n in the last panel are zero.
//
// The kernels never reassociate a sum across a fixed order: each entry of a product sums its
// terms panel by panel, inside a panel the even and the odd rows separately (the two SSE lanes),
// then odd onto even, then onto the running total; subtractions run over the basis columns in
// increasing order. With a WorkerPool the outputs are split (coefficient rows or panels), each
// computed exactly as without it, so results do not depend on the number of threads.
#pragma once
#include <Eigen/Core>
#include <vector>

#include "util/parallel.h"

namespace offsetopt {

constexpr Eigen::Index kPanelRows = 128;

class PanelMatrix {
 public:
  PanelMatrix() = default;
  PanelMatrix(Eigen::Index rows, int cols) { resize(rows, cols); }
  // Discards the contents; everything (padding included) is zero afterwards.
  void resize(Eigen::Index rows, int cols);
  // Keeps the first min(old, new) columns (the rows are unchanged).
  void resize_columns(int cols);

  Eigen::Index rows() const { return rows_; }
  int cols() const { return cols_; }
  Eigen::Index panels() const { return panels_; }
  // The kPanelRows entries of column `col` in panel `panel`.
  double* column(Eigen::Index panel, int col) { return data_.data() + (panel * cols_ + col) * kPanelRows; }
  const double* column(Eigen::Index panel, int col) const {
    return data_.data() + (panel * cols_ + col) * kPanelRows;
  }
  double& operator()(Eigen::Index row, int col) { return column(row / kPanelRows, col)[row % kPanelRows]; }
  double operator()(Eigen::Index row, int col) const { return column(row / kPanelRows, col)[row % kPanelRows]; }

  // Copies between columns [col, col + width) and a row-major n by width block (row stride ld).
  void set_columns(int col, int width, const double* rows_major, Eigen::Index ld);
  void get_columns(int col, int width, double* rows_major, Eigen::Index ld) const;
  // Copies columns [from, from + width) of `source` into columns [col, col + width).
  void copy_columns(int col, const PanelMatrix& source, int from, int width);

 private:
  Eigen::Index rows_ = 0, panels_ = 0;
  int cols_ = 0;
  std::vector<double, Eigen::aligned_allocator<double>> data_;
};

// C (j by b, row-major) = A(:, a0 : a0 + j)ᵀ B(:, b0 : b0 + b).
void panel_project(const PanelMatrix& A, int a0, int j, const PanelMatrix& B, int b0, int b, double* C,
                   WorkerPool* pool = nullptr);

// B(:, b0 : b0 + b) -= A(:, a0 : a0 + j) C, C j by b row-major.
void panel_subtract(const PanelMatrix& A, int a0, int j, const double* C, PanelMatrix& B, int b0, int b,
                    WorkerPool* pool = nullptr);

// X(:, x0 : x0 + p) = A(:, a0 : a0 + j) Z, Z j by p row-major. X may be A itself (each panel is
// computed into a buffer first).
void panel_combine(const PanelMatrix& A, int a0, int j, const double* Z, int p, PanelMatrix& X, int x0,
                   WorkerPool* pool = nullptr);

// Euclidean norms of columns [c0, c0 + b), rows summed in order.
Eigen::VectorXd panel_column_norms(const PanelMatrix& A, int c0, int b);

}  // namespace offsetopt
