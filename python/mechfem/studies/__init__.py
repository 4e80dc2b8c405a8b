"""Many runs: sweeps and ``run_many``, tolerance studies and bands, the cluster executor. Imports the packages up to
``run``."""
