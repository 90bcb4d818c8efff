"""lcm_control's benchmarks as a package: bench/run is its entry point, and the scripts beside it (bench/pacing,
bench/robots, bench/dashboard, bench/xacro) import its modules: processes (children through tools/lib/process), ports
(a free LCM URL), robots (the chain URDFs), one module per benchmark, the table and the results writer."""
import os

HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))  # bench/
REPO = os.path.dirname(HERE)
