"""The output files of a command: the print file and data set, their formats, the media and the output folder.
Imports the packages up to ``report``."""
