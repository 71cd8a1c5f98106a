"""Work-precision scripts (not tests): ``python -m verify.benchmarks.<name> [out_dir]``."""
