/* placeholder: being written */ typedef int rugo__placeholder_wavelet;
