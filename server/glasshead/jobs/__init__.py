"""Work that runs outside the server's own process: the worker pool (``pool``), the compute
pool of the heavy routes and of speech (``compute``) and the fit jobs (``fit_job``,
``fit_runner``)."""
