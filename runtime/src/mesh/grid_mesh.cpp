// The regular-grid mesh of a heightfield: vertices at the sampled pixels, normals from central
// differences at the true spacing, two counter-clockwise triangles per cell; optionally every border
// sample kept and fanned into the coarse border cells.
#include <algorithm>
#include <cmath>

#include "mesh/mesh_steps.h"

namespace terrasynth::mesh_detail {

std::vector<int> gridSamples(int size, int border, int step) {
    const int last = size - border - 1;
    std::vector<int> samples;
    for (int s = border; s < last; s += step) samples.push_back(s);
    samples.push_back(last);
    return samples;
}

namespace {

// Unit normal (z up, y north) at field pixel (x, y) from differences over +-d pixels, clamped to the
// field: central where the apron allows, one-sided at the field's own edge.
void normalAt(const Heightfield& field, int x, int y, int d, float* out) {
    const int xl = std::max(x - d, 0), xr = std::min(x + d, field.width - 1);
    const int yt = std::max(y - d, 0), yb = std::min(y + d, field.height - 1);
    const double dz_dx = xr > xl ? (field.at(xr, y) - field.at(xl, y)) / ((xr - xl) * field.meters_per_pixel_x) : 0.0;
    // Rows grow south, so the northward slope is minus the southward one.
    const double dz_dsouth =
        yb > yt ? (field.at(x, yb) - field.at(x, yt)) / ((yb - yt) * field.meters_per_pixel_y) : 0.0;
    const double nx = -dz_dx, ny = dz_dsouth, nz = 1.0;
    const double inv = 1.0 / std::sqrt(nx * nx + ny * ny + nz * nz);
    out[0] = static_cast<float>(nx * inv);
    out[1] = static_cast<float>(ny * inv);
    out[2] = static_cast<float>(nz * inv);
}

class GridBuilder {
public:
    GridBuilder(const Heightfield& field, const MeshOptions& options, const std::vector<int>& cols,
                const std::vector<int>& rows)
        : field_(field), options_(options), cols_(cols), rows_(rows), nc_(cols.size()), nr_(rows.size()),
          b_(options.border), x_last_(cols.back()), y_last_(rows.back()),
          span_x_(std::max(x_last_ - b_, 1)), span_y_(std::max(y_last_ - b_, 1)) {}

    TileMesh build() {
        for (int y : rows_)
            for (int x : cols_) addVertex(x, y);
        if (options_.full_res_border) addFineBorder();
        if (nc_ >= 2 && nr_ >= 2) addCells();
        return std::move(mesh_);
    }

    // Clockwise (seen from above) ring of every border vertex the mesh has, from the north-west corner.
    std::vector<uint32_t> ring() const {
        std::vector<uint32_t> out;
        if (nc_ < 2 || nr_ < 2) return out;
        for (int x = b_; x < x_last_; ++x) pushIfPresent(out, x, b_);            // north, eastward
        for (int y = b_; y < y_last_; ++y) pushIfPresent(out, x_last_, y);       // east, southward
        for (int x = x_last_; x > b_; --x) pushIfPresent(out, x, y_last_);       // south, westward
        for (int y = y_last_; y > b_; --y) pushIfPresent(out, b_, y);            // west, northward
        return out;
    }

private:
    bool onBorder(int x, int y) const { return x == b_ || x == x_last_ || y == b_ || y == y_last_; }

    uint32_t addVertex(int x, int y) {
        const uint32_t id = static_cast<uint32_t>(mesh_.vertexCount());
        mesh_.positions.push_back(static_cast<float>(options_.origin_x_m + (x - b_) * field_.meters_per_pixel_x));
        mesh_.positions.push_back(static_cast<float>(options_.origin_y_m - (y - b_) * field_.meters_per_pixel_y));
        mesh_.positions.push_back(field_.at(x, y));
        // A full-resolution border takes 1-pixel differences, the same at every step, so shading
        // matches across a seam between LODs.
        const int d = options_.full_res_border && onBorder(x, y) ? 1 : options_.step;
        float n[3];
        normalAt(field_, x, y, d, n);
        mesh_.normals.insert(mesh_.normals.end(), n, n + 3);
        mesh_.uvs.push_back(static_cast<float>(double(x - b_) / span_x_));
        mesh_.uvs.push_back(static_cast<float>(double(y - b_) / span_y_));
        return id;
    }

    // Fine (non-grid) border samples, indexed by their offset along each side.
    void addFineBorder() {
        const int w = x_last_ - b_ + 1, h = y_last_ - b_ + 1;
        north_.assign(w, ~0u), south_.assign(w, ~0u), west_.assign(h, ~0u), east_.assign(h, ~0u);
        std::vector<char> grid_x(w, 0), grid_y(h, 0);
        for (int x : cols_) grid_x[x - b_] = 1;
        for (int y : rows_) grid_y[y - b_] = 1;
        for (int x = b_; x <= x_last_; ++x) {
            if (grid_x[x - b_]) continue;
            north_[x - b_] = addVertex(x, b_);
            if (nr_ > 1) south_[x - b_] = addVertex(x, y_last_);
        }
        for (int y = b_; y <= y_last_; ++y) {
            if (grid_y[y - b_]) continue;
            west_[y - b_] = addVertex(b_, y);
            if (nc_ > 1) east_[y - b_] = addVertex(x_last_, y);
        }
    }

    uint32_t gridId(size_t i, size_t j) const { return static_cast<uint32_t>(j * nc_ + i); }

    // The vertex at border pixel (x, y): a grid vertex or a fine one; ~0u when absent.
    uint32_t borderVertex(int x, int y) const {
        const auto ci = std::lower_bound(cols_.begin(), cols_.end(), x);
        const auto rj = std::lower_bound(rows_.begin(), rows_.end(), y);
        if (ci != cols_.end() && *ci == x && rj != rows_.end() && *rj == y)
            return gridId(ci - cols_.begin(), rj - rows_.begin());
        if (north_.empty()) return ~0u;
        if (y == b_) return north_[x - b_];
        if (y == y_last_) return south_[x - b_];
        if (x == b_) return west_[y - b_];
        if (x == x_last_) return east_[y - b_];
        return ~0u;
    }

    void pushIfPresent(std::vector<uint32_t>& out, int x, int y) const {
        const uint32_t v = borderVertex(x, y);
        if (v != ~0u) out.push_back(v);
    }

    void addCells() {
        mesh_.indices.reserve((nc_ - 1) * (nr_ - 1) * 6 + 12 * (nc_ + nr_));
        // Vertical bands of kBand cells, row by row inside a band: each row reuses the kBand+1
        // vertices of the row above, and both rows (16 vertices) fit a 16-entry post-transform cache
        // (ACMR about 0.6 against 1.0 row-major; meshoptimizer's optimiser is 4x slower here).
        constexpr size_t kBand = 7;
        for (size_t band = 0; band + 1 < nc_; band += kBand)
        for (size_t j = 0; j + 1 < nr_; ++j) {
            for (size_t i = band; i + 1 < nc_ && i < band + kBand; ++i) {
                const bool stitched = options_.full_res_border && (i == 0 || j == 0 || i + 2 == nc_ || j + 2 == nr_);
                if (stitched) {
                    addStitchedCell(i, j);
                    continue;
                }
                // a b    (north row)    Seen from above (y north) a,c,b and b,c,d are
                // c d    (south row)    counter-clockwise.
                const uint32_t a = gridId(i, j), b = a + 1, c = gridId(i, j + 1), d = c + 1;
                mesh_.indices.insert(mesh_.indices.end(), {a, c, b, b, c, d});
            }
        }
    }

    // A border cell with fine samples on its border side(s): walk its outline counter-clockwise
    // (NW, down the west side, along the south, up the east, back along the north) and fan it from a
    // corner that touches no subdivided side, so no fan triangle is degenerate.
    void addStitchedCell(size_t i, size_t j) {
        const int x0 = cols_[i], x1 = cols_[i + 1], y0 = rows_[j], y1 = rows_[j + 1];
        const bool west = i == 0, east = i + 2 == nc_, north = j == 0, south = j + 2 == nr_;
        std::vector<uint32_t> outline;
        std::vector<char> corner;  // which outline entries are cell corners
        auto push = [&](uint32_t v, bool is_corner) { outline.push_back(v); corner.push_back(is_corner); };
        push(gridId(i, j), true);
        if (west) for (int y = y0 + 1; y < y1; ++y) push(west_[y - b_], false);
        push(gridId(i, j + 1), true);
        if (south) for (int x = x0 + 1; x < x1; ++x) push(south_[x - b_], false);
        push(gridId(i + 1, j + 1), true);
        if (east) for (int y = y1 - 1; y > y0; --y) push(east_[y - b_], false);
        push(gridId(i + 1, j), true);
        if (north) for (int x = x1 - 1; x > x0; --x) push(north_[x - b_], false);
        // Corners in outline order are NW, SW, SE, NE; each touches two sides.
        const bool touches_subdivided[4] = {west || north, west || south, south || east, east || north};
        const size_t n = outline.size();
        size_t apex = n, k = 0;
        for (size_t p = 0; p < n && apex == n; ++p) {
            if (!corner[p]) continue;
            if (!touches_subdivided[k]) apex = p;
            ++k;
        }
        // A cell on two opposite borders (a tile one cell wide, e.g. the last tile of a region that
        // tile_size does not divide): a corner whose sides have no fine samples after all, else a
        // vertex at the cell's centre, so no fan triangle lies along a subdivided side.
        for (size_t p = 0; p < n && apex == n; ++p)
            if (corner[p] && corner[(p + 1) % n] && corner[(p + n - 1) % n]) apex = p;
        if (apex == n) {
            const uint32_t centre = addCentreVertex(gridId(i, j), gridId(i + 1, j), gridId(i, j + 1), gridId(i + 1, j + 1));
            for (size_t m = 0; m < n; ++m) mesh_.indices.insert(mesh_.indices.end(), {centre, outline[m], outline[(m + 1) % n]});
            return;
        }
        for (size_t m = 1; m + 1 < n; ++m)
            mesh_.indices.insert(mesh_.indices.end(),
                                 {outline[apex], outline[(apex + m) % n], outline[(apex + m + 1) % n]});
    }

    // A vertex at the centre of the cell with these corners: the mean of their positions, normals
    // and texture coordinates (the bilinear surface there).
    uint32_t addCentreVertex(uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
        const uint32_t id = static_cast<uint32_t>(mesh_.vertexCount());
        const uint32_t corners[4] = {a, b, c, d};
        float position[3] = {0, 0, 0}, normal[3] = {0, 0, 0}, uv[2] = {0, 0};
        for (uint32_t v : corners) {
            for (int k = 0; k < 3; ++k) position[k] += 0.25f * mesh_.positions[3 * v + k];
            for (int k = 0; k < 3; ++k) normal[k] += mesh_.normals[3 * v + k];
            for (int k = 0; k < 2; ++k) uv[k] += 0.25f * mesh_.uvs[2 * v + k];
        }
        const float length = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
        for (float& v : normal) v = length > 0.0f ? v / length : 0.0f;
        if (length == 0.0f) normal[2] = 1.0f;
        mesh_.positions.insert(mesh_.positions.end(), position, position + 3);
        mesh_.normals.insert(mesh_.normals.end(), normal, normal + 3);
        mesh_.uvs.insert(mesh_.uvs.end(), uv, uv + 2);
        return id;
    }

    const Heightfield& field_;
    const MeshOptions& options_;
    const std::vector<int>& cols_;
    const std::vector<int>& rows_;
    const size_t nc_, nr_;
    const int b_, x_last_, y_last_;
    const int span_x_, span_y_;
    std::vector<uint32_t> north_, south_, west_, east_;
    TileMesh mesh_;
};

}  // namespace

TileMesh buildGrid(const Heightfield& field, const MeshOptions& options, const std::vector<int>& cols,
                   const std::vector<int>& rows, std::vector<uint32_t>* ring) {
    GridBuilder builder(field, options, cols, rows);
    TileMesh mesh = builder.build();
    *ring = builder.ring();
    return mesh;
}

}  // namespace terrasynth::mesh_detail
