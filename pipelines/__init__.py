"""What users run: build modal bodies, report; the ``axlebox`` command line."""
