"""Offline trainers, run by ``glasshead train``: the coarticulation constants
(``coarticulation``) fitted against VocalTractLab's gestural trajectories carried into our
parameters (``vtl_reference``). Nothing at run time imports this package: the trained constants
are a definition file the speech code reads."""
