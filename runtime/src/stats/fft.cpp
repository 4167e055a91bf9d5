// Iterative Cooley-Tukey radix-2 FFT: bit-reversal permutation, then log2(n) butterfly passes.
#include "stats/fft.h"

#include <cmath>
#include <utility>

#include "terrasynth/status.h"

namespace terrasynth::stats {

bool isPowerOfTwo(int n) { return n > 0 && (n & (n - 1)) == 0; }

void fft(std::complex<double>* a, int n, bool inverse) {
    TERRASYNTH_REQUIRE(isPowerOfTwo(n), "FFT length must be a power of two");
    for (int i = 1, j = 0; i < n; ++i) {
        int bit = n >> 1;
        for (; j & bit; bit >>= 1) j ^= bit;
        j ^= bit;
        if (i < j) std::swap(a[i], a[j]);
    }
    const double sign = inverse ? 1.0 : -1.0;
    for (int len = 2; len <= n; len <<= 1) {
        const double angle = sign * 2.0 * 3.14159265358979323846 / len;
        const std::complex<double> step(std::cos(angle), std::sin(angle));
        for (int start = 0; start < n; start += len) {
            std::complex<double> w(1.0, 0.0);
            for (int k = 0; k < len / 2; ++k) {
                const std::complex<double> u = a[start + k];
                const std::complex<double> v = a[start + k + len / 2] * w;
                a[start + k] = u + v;
                a[start + k + len / 2] = u - v;
                w *= step;
            }
        }
    }
    if (inverse)
        for (int i = 0; i < n; ++i) a[i] /= static_cast<double>(n);
}

void fft2d(std::vector<std::complex<double>>& data, int n, bool inverse) {
    TERRASYNTH_REQUIRE(data.size() == static_cast<size_t>(n) * n, "2D FFT needs n*n samples");
    for (int y = 0; y < n; ++y) fft(&data[static_cast<size_t>(y) * n], n, inverse);
    std::vector<std::complex<double>> column(n);
    for (int x = 0; x < n; ++x) {
        for (int y = 0; y < n; ++y) column[y] = data[static_cast<size_t>(y) * n + x];
        fft(column.data(), n, inverse);
        for (int y = 0; y < n; ++y) data[static_cast<size_t>(y) * n + x] = column[y];
    }
}

}  // namespace terrasynth::stats
