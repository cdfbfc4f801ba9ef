#include "GlyphReader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

namespace mvw::test::reader {

double grey(const Image& im, int x, int y) {
  const auto* p = im.pixel(x, y);
  return (p[0] + p[1] + p[2]) / 3.0;
}

std::vector<double> glyphChange(const Image& glyphs, const Image& plain) {
  std::vector<double> d(std::size_t(glyphs.width) * glyphs.height);
  for (int y = 0; y < glyphs.height; ++y)
    for (int x = 0; x < glyphs.width; ++x)
      d[std::size_t(y) * glyphs.width + x] = grey(glyphs, x, y) - grey(plain, x, y);
  return d;
}

std::vector<Blob> changedBlobs(const std::vector<double>& d, int w, int h) {
  std::vector<char> grown(d.size(), 0);
  for (int y = 1; y < h - 1; ++y)
    for (int x = 1; x < w - 1; ++x)
      if (std::abs(d[std::size_t(y) * w + x]) >= kChanged)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) grown[std::size_t(y + dy) * w + x + dx] = 1;
  std::vector<char> seen(d.size(), 0);
  std::vector<Blob> blobs;
  for (int start = 0; start < w * h; ++start) {
    if (!grown[std::size_t(start)] || seen[std::size_t(start)]) continue;
    Blob blob;
    blob.pixels = {start};
    std::vector<int> stack = {start};
    seen[std::size_t(start)] = 1;
    while (!stack.empty()) {
      const int p = stack.back();
      stack.pop_back();
      const int x = p % w, y = p / w;
      blob.edge |= x == 0 || y == 0 || x == w - 1 || y == h - 1;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx < 0 || yy < 0 || xx >= w || yy >= h) continue;
          const int q = yy * w + xx;
          if (grown[std::size_t(q)] && !seen[std::size_t(q)])
            seen[std::size_t(q)] = 1, blob.pixels.push_back(q), stack.push_back(q);
        }
    }
    double cx = 0.0, cy = 0.0;
    for (int p : blob.pixels) cx += p % w, cy += p / w;
    const double area = double(blob.pixels.size());
    blob.middle = int(std::lround(cy / area)) * w + int(std::lround(cx / area));
    blobs.push_back(std::move(blob));
  }
  return blobs;
}

bool isGlyphPatch(const Blob& blob, double glyphRadiusPx) {
  const double area = double(blob.pixels.size()), disc = M_PI * glyphRadiusPx * glyphRadiusPx;
  return !blob.edge && area >= 0.25 * disc && area <= 1.6 * disc;
}

Features describe(const std::vector<double>& d, int w, const std::vector<int>& pixels,
                  double glyphRadiusPx) {
  double cx = 0.0, cy = 0.0;
  for (int p : pixels) cx += p % w, cy += p / w;
  cx /= pixels.size(), cy /= pixels.size();
  double sxx = 0.0, syy = 0.0, sxy = 0.0, sumAbs = 0.0, sumD = 0.0, light = 0.0;
  std::array<double, 3> ringAbs{}, ringChanged{}, ringCount{};
  std::array<double, 16> sector{};
  const double rho = std::sqrt(pixels.size() / M_PI);
  for (int p : pixels) {
    const double x = p % w - cx, y = p / w - cy, v = d[std::size_t(p)];
    sxx += x * x, syy += y * y, sxy += x * y;
    sumAbs += std::abs(v), sumD += v;
    light += v * (-x - y) / std::sqrt(2.0) / rho;  // toward the upper left (image y down)
    const double r = std::sqrt(x * x + y * y) / rho;
    const int ring = r < 0.4 ? 0 : r < 0.75 ? 1 : 2;
    ringAbs[std::size_t(ring)] += std::abs(v), ringCount[std::size_t(ring)] += 1.0;
    const bool changed = std::abs(v) >= kChanged;
    ringChanged[std::size_t(ring)] += changed;
    if (changed && r > 0.25) {
      const int s = int((std::atan2(y, x) + M_PI) / (2.0 * M_PI) * 16.0) % 16;
      sector[std::size_t(s)] += 1.0;
    }
  }
  const double tr = sxx + syy, det = sxx * syy - sxy * sxy;
  const double root = std::sqrt(std::max(tr * tr / 4.0 - det, 0.0));
  const double elongation = std::sqrt(std::max(tr / 2.0 - root, 0.0) / (tr / 2.0 + root + 1e-9));
  auto harmonic = [&](int m) {
    double c = 0.0, s = 0.0, total = 0.0;
    for (int i = 0; i < 16; ++i) {
      const double a = (i + 0.5) * 2.0 * M_PI / 16.0;
      c += sector[std::size_t(i)] * std::cos(m * a), s += sector[std::size_t(i)] * std::sin(m * a);
      total += sector[std::size_t(i)];
    }
    return total > 0.0 ? std::sqrt(c * c + s * s) / total : 0.0;
  };
  const double meanAbs = sumAbs / pixels.size() + 1e-9;
  // The signed and the absolute change in five rings of the glyph's disc, against the mean.
  std::array<double, 5> profile{}, profileAbs{}, profileN{};
  for (int p : pixels) {
    const double x = p % w - cx, y = p / w - cy, v = d[std::size_t(p)];
    const int ring = std::min(4, int(std::sqrt(x * x + y * y) / rho * 4.0));
    profile[std::size_t(ring)] += v, profileAbs[std::size_t(ring)] += std::abs(v);
    profileN[std::size_t(ring)] += 1.0;
  }
  for (int i = 0; i < 5; ++i) {
    profile[std::size_t(i)] /= std::max(profileN[std::size_t(i)], 1.0) * meanAbs;
    profileAbs[std::size_t(i)] /= std::max(profileN[std::size_t(i)], 1.0) * meanAbs;
  }
  Features f{};
  f = {elongation,
       ringAbs[0] / std::max(ringCount[0], 1.0) / meanAbs,
       ringAbs[1] / std::max(ringCount[1], 1.0) / meanAbs,
       ringAbs[2] / std::max(ringCount[2], 1.0) / meanAbs,
       ringChanged[0] / std::max(ringCount[0], 1.0),
       ringChanged[1] / std::max(ringCount[1], 1.0),
       ringChanged[2] / std::max(ringCount[2], 1.0),
       harmonic(2),
       harmonic(4),
       sumD / sumAbs,
       light / (sumAbs + 1e-9),
       rho / glyphRadiusPx,
       profile[0],
       profile[1],
       profile[2],
       profile[3],
       profile[4],
       profileAbs[0],
       profileAbs[1],
       profileAbs[2],
       profileAbs[3],
       profileAbs[4]};
  return f;
}

Result classify(const std::vector<Tile>& tiles, int kinds) {
  Features mean{}, spread{};
  for (const Tile& t : tiles)
    for (int i = 0; i < kFeatures; ++i) mean[i] += t.f[i] / tiles.size();
  for (const Tile& t : tiles)
    for (int i = 0; i < kFeatures; ++i)
      spread[i] += (t.f[i] - mean[i]) * (t.f[i] - mean[i]) / tiles.size();
  for (double& s : spread) s = std::sqrt(s) + 1e-9;
  // Three cues a reader looks at first weigh more: the side the light brightens (bumps against
  // dimples), and the two- and four-fold pattern around the centre (bars, crosses).
  spread[10] /= 3.0, spread[7] /= 2.0, spread[8] /= 2.0;
  std::vector<double> count(std::size_t(kinds), 1e-9);
  for (const Tile& t : tiles) count[std::size_t(t.truth)] += 1.0;
  Result r;
  r.confusion.assign(std::size_t(kinds), std::vector<int>(std::size_t(kinds), 0));
  for (const Tile& t : tiles) {
    std::vector<std::pair<double, int>> near;
    for (const Tile& o : tiles) {
      if (o.group == t.group) continue;
      double d2 = 0.0;
      for (int i = 0; i < kFeatures; ++i) {
        const double d = (t.f[i] - o.f[i]) / spread[i];
        d2 += d * d;
      }
      near.emplace_back(d2, o.truth);
    }
    const std::size_t k = std::min<std::size_t>(7, near.size());
    std::partial_sort(near.begin(), near.begin() + long(k), near.end());
    // Each neighbour's vote weighs 1 / (its kind's share of the tiles): a kind with many
    // glyphs in view (bars split, a band seen face-on) does not outvote the others.
    std::vector<double> votes(std::size_t(kinds), 0.0);
    for (std::size_t i = 0; i < k; ++i)
      votes[std::size_t(near[i].second)] += 1.0 / count[std::size_t(near[i].second)];
    const int assigned = int(std::max_element(votes.begin(), votes.end()) - votes.begin());
    const int truth = t.truth;
    ++r.confusion[std::size_t(truth)][std::size_t(assigned)];
    r.right += assigned == truth, ++r.total;
  }
  return r;
}

void print(const Result& r, const std::vector<std::string>& names, const char* title) {
  std::printf("\n%s: %d of %d glyph patches (%.1f %%) assigned the kind drawn there\n%-9s", title,
              r.right, r.total, 100.0 * r.right / std::max(r.total, 1), "truth \\ as");
  for (const std::string& n : names) std::printf(" %8s", n.c_str());
  std::printf("\n");
  for (std::size_t i = 0; i < names.size(); ++i) {
    std::printf("%-9s", names[i].c_str());
    for (int c : r.confusion[i]) std::printf(" %8d", c);
    std::printf("\n");
  }
}

}  // namespace mvw::test::reader
