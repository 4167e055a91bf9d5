// Radix-2 complex FFT for the power spectrum (and for tests that synthesise fractal surfaces).
#pragma once

#include <complex>
#include <vector>

namespace terrasynth::stats {

// In-place discrete Fourier transform of a power-of-two length sequence. Forward: X_k = sum x_n
// e^{-2 pi i k n / N}; inverse uses +i and divides by N.
void fft(std::complex<double>* data, int n, bool inverse);

// In-place 2D transform of an n x n row-major array (n a power of two): rows, then columns.
void fft2d(std::vector<std::complex<double>>& data, int n, bool inverse);

bool isPowerOfTwo(int n);

}  // namespace terrasynth::stats
