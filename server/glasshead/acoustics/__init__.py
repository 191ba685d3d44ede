"""The acoustics of a vocal tract given as a tube of sections: its transfer function and
formants (``tube``)."""
