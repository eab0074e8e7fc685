/* filled in below */ typedef int reference_placeholder;
