"""Work that runs outside the server's own process: the worker pool (``pool``), the compute
pool of the heavy routes and of speech (``compute``) and the fit jobs: the queue in the database
(``fit_queue``), one job in a worker (``fit_job``) and each server's workers taking jobs from
the queue (``fit_runner``)."""
