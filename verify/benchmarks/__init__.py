"""Work-precision scripts (not tests): ``python -m landau.verify.benchmarks.<name> [out_dir]``."""
